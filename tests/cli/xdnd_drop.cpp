// xdnd_drop: drops files onto an X11 window the way a file manager does, by the XDND protocol
// (version 5, freedesktop.org): enter, position, drop, then the file list served as
// text/uri-list from the XdndSelection, waiting for the target's status and finished messages.
// For view_test, which drops models and environments onto `fresnel view` under Xvfb.
//
//   xdnd_drop WINDOW_ID X Y FILE...     (X, Y: the drop point in the window; exit 0 when the
//                                        target accepted and finished, 1 otherwise)
#include <X11/Xatom.h>
#include <X11/Xlib.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

namespace {

struct Atoms {
    Atom aware, enter, position, status, drop, finished, selection, action_copy, uri_list;
    explicit Atoms(Display* d)
        : aware(XInternAtom(d, "XdndAware", False)),
          enter(XInternAtom(d, "XdndEnter", False)),
          position(XInternAtom(d, "XdndPosition", False)),
          status(XInternAtom(d, "XdndStatus", False)),
          drop(XInternAtom(d, "XdndDrop", False)),
          finished(XInternAtom(d, "XdndFinished", False)),
          selection(XInternAtom(d, "XdndSelection", False)),
          action_copy(XInternAtom(d, "XdndActionCopy", False)),
          uri_list(XInternAtom(d, "text/uri-list", False)) {}
};

void send(Display* d, Window target, Atom type, long l0, long l1, long l2, long l3, long l4) {
    XEvent e;
    std::memset(&e, 0, sizeof e);
    e.xclient.type = ClientMessage;
    e.xclient.display = d;
    e.xclient.window = target;
    e.xclient.message_type = type;
    e.xclient.format = 32;
    e.xclient.data.l[0] = l0;
    e.xclient.data.l[1] = l1;
    e.xclient.data.l[2] = l2;
    e.xclient.data.l[3] = l3;
    e.xclient.data.l[4] = l4;
    XSendEvent(d, target, False, NoEventMask, &e);
    XFlush(d);
}

// "file:///a%20b/c.glb\r\n" per file (RFC 2483), absolute paths, reserved bytes escaped.
std::string uri_list(const std::vector<std::string>& files) {
    std::string out;
    for (const std::string& f : files) {
        out += "file://";
        for (unsigned char c : f) {
            if (std::isalnum(c) || std::strchr("/-._~", c)) out += char(c);
            else {
                char buf[4];
                std::snprintf(buf, sizeof buf, "%%%02X", c);
                out += buf;
            }
        }
        out += "\r\n";
    }
    return out;
}

int fail(const char* why) {
    std::fprintf(stderr, "xdnd_drop: %s\n", why);
    return 1;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 5) return fail("usage: xdnd_drop WINDOW_ID X Y FILE...");
    Window target = Window(std::strtoul(argv[1], nullptr, 0));
    int x = std::atoi(argv[2]), y = std::atoi(argv[3]);
    std::vector<std::string> files(argv + 4, argv + argc);
    Display* d = XOpenDisplay(nullptr);
    if (!d) return fail("cannot open the display");
    Atoms a(d);

    // The target must say it speaks XDND, and which version.
    Atom type = None;
    int format = 0;
    unsigned long count = 0, after = 0;
    unsigned char* data = nullptr;
    if (XGetWindowProperty(d, target, a.aware, 0, 1, False, XA_ATOM, &type, &format, &count, &after, &data) !=
            Success ||
        count != 1 || !data)
        return fail("the window is not XdndAware");
    long version = std::min<long>(5, long(*reinterpret_cast<Atom*>(data)));
    XFree(data);

    Window source = XCreateSimpleWindow(d, DefaultRootWindow(d), 0, 0, 1, 1, 0, 0, 0);
    XSelectInput(d, source, PropertyChangeMask);
    XSetSelectionOwner(d, a.selection, source, CurrentTime);
    int root_x = 0, root_y = 0;
    Window child;
    XTranslateCoordinates(d, target, DefaultRootWindow(d), x, y, &root_x, &root_y, &child);

    const std::string payload = uri_list(files);
    send(d, target, a.enter, long(source), version << 24, long(a.uri_list), 0, 0);
    send(d, target, a.position, long(source), 0, (long(root_x) << 16) | long(root_y), CurrentTime,
         long(a.action_copy));

    // Drop once the target has answered the position, serve the selection, wait for finished.
    bool dropped = false, accepted = false;
    auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < std::chrono::seconds(20)) {
        if (!XPending(d)) {
            struct timespec ts = {0, 10 * 1000 * 1000};
            nanosleep(&ts, nullptr);
            continue;
        }
        XEvent e;
        XNextEvent(d, &e);
        if (e.type == ClientMessage && e.xclient.message_type == a.status && !dropped) {
            accepted = (e.xclient.data.l[1] & 1) != 0;
            if (!accepted) return fail("the target refused the drop");
            send(d, target, a.drop, long(source), 0, CurrentTime, 0, 0);
            dropped = true;
        } else if (e.type == SelectionRequest) {
            const XSelectionRequestEvent& r = e.xselectionrequest;
            XEvent reply;
            std::memset(&reply, 0, sizeof reply);
            reply.xselection.type = SelectionNotify;
            reply.xselection.display = d;
            reply.xselection.requestor = r.requestor;
            reply.xselection.selection = r.selection;
            reply.xselection.target = r.target;
            reply.xselection.time = r.time;
            reply.xselection.property = None;
            if (r.target == a.uri_list) {
                XChangeProperty(d, r.requestor, r.property, a.uri_list, 8, PropModeReplace,
                                reinterpret_cast<const unsigned char*>(payload.data()), int(payload.size()));
                reply.xselection.property = r.property;
            }
            XSendEvent(d, r.requestor, False, NoEventMask, &reply);
            XFlush(d);
        } else if (e.type == ClientMessage && e.xclient.message_type == a.finished) {
            XDestroyWindow(d, source);
            XCloseDisplay(d);
            return 0;
        }
    }
    return fail(dropped ? "no XdndFinished from the target" : "no XdndStatus from the target");
}
