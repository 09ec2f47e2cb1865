// write_file_atomically and FileSet: whole or absent (a file, a set of files), the originals
// kept on failure, unique temporaries per thread, a killed writer's temporaries cleaned,
// errors naming the destination and the system's reason.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstring>

#include <atomic>
#include <mutex>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "fresnel/core/atomic_file.h"
#include "fresnel/core/error.h"
#include "file_size_limit.h"

using namespace fresnel;
namespace fs = std::filesystem;

namespace {
std::string read_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}
struct Scratch {
    fs::path dir = fs::temp_directory_path() / ("fresnel_atomic_" + std::to_string(::getpid()));
    Scratch() { fs::create_directories(dir); }
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
    std::size_t entries() const {
        return std::size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
    }
};
}  // namespace
using fresnel::test::FileSizeLimit;

TEST(AtomicFile, WritesAndReplacesWhole) {
    Scratch s;
    const fs::path f = s.dir / "out.txt";
    write_file_atomically(f, std::string_view("first"));
    EXPECT_EQ(read_text(f), "first");
    write_file_atomically(f, std::string_view("second, longer"));
    EXPECT_EQ(read_text(f), "second, longer");
    EXPECT_EQ(s.entries(), 1u);  // no temporary left behind
}

TEST(AtomicFile, AFailedWriteLeavesTheOriginalAndNoTemporary) {
    Scratch s;
    const fs::path f = s.dir / "image.png";
    write_file_atomically(f, std::string_view("the good one"));
    try {
        write_file_atomically(f, [](const fs::path& tmp) {
            EXPECT_EQ(tmp.extension(), ".png");  // writers that look at the extension see it
            EXPECT_EQ(tmp.parent_path(), fs::path(tmp).parent_path());
            std::ofstream(tmp) << "half";
            throw Error(tmp.string(), "row 7", "the disk is full");
        });
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), f.string());  // the destination, not the temporary
        EXPECT_EQ(e.where(), "row 7");
        EXPECT_EQ(e.reason(), "the disk is full");
    }
    EXPECT_EQ(read_text(f), "the good one");
    EXPECT_EQ(s.entries(), 1u);
}

TEST(AtomicFile, AnUnwritableFolderIsAnErrorNamingTheDestination) {
    Scratch s;
    const fs::path f = s.dir / "no" / "such" / "folder" / "x.bin";
    const std::vector<std::uint8_t> bytes = {1, 2, 3};
    try {
        write_file_atomically(f, std::span<const std::uint8_t>(bytes));
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), f.string());
    }
    EXPECT_FALSE(fs::exists(f));
}

TEST(AtomicFile, TemporariesAreUniquePerThread) {
    const fs::path f = "/somewhere/out.exr";
    std::set<std::string> names;
    std::mutex m;
    std::vector<std::thread> threads;
    for (int i = 0; i < 8; ++i)
        threads.emplace_back([&] {
            const std::string n = temporary_path_beside(f).string();
            std::lock_guard lock(m);
            names.insert(n);
        });
    for (auto& t : threads) t.join();
    EXPECT_EQ(names.size(), 8u);
    for (const auto& n : names) {
        EXPECT_EQ(fs::path(n).parent_path(), "/somewhere");
        EXPECT_EQ(fs::path(n).extension(), ".exr");
        EXPECT_EQ(fs::path(n).filename().string().front(), '.');
    }
}

TEST(AtomicFile, ThreadsWritingOneFileLeaveOneWholeVersion) {
    Scratch s;
    const fs::path f = s.dir / "shared.txt";
    std::vector<std::thread> threads;
    std::atomic<int> failures{0};
    for (int i = 0; i < 8; ++i)
        threads.emplace_back([&, i] {
            const std::string text(4096 + i, char('a' + i));
            for (int k = 0; k < 20; ++k) {
                try {
                    write_file_atomically(f, std::string_view(text));
                } catch (const Error&) {
                    ++failures;
                }
            }
        });
    for (auto& t : threads) t.join();
    EXPECT_EQ(failures.load(), 0);
    const std::string text = read_text(f);
    ASSERT_FALSE(text.empty());
    const int i = text.front() - 'a';
    EXPECT_EQ(text, std::string(4096 + i, char('a' + i)));  // one writer's whole content
    EXPECT_EQ(s.entries(), 1u);
}

namespace {
// A PID that was a process and is no more.
long dead_pid() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    int status = 0;
    ::waitpid(child, &status, 0);
    return long(child);
}
}  // namespace

TEST(AtomicFile, AShortWriteFailsAndKeepsTheOldFile) {
    Scratch s;
    const fs::path f = s.dir / "frame.bin";
    write_file_atomically(f, std::string_view("the good one"));
    const std::vector<std::uint8_t> big(64 * 1024, 7);
    try {
        FileSizeLimit limit(4096);
        write_file_atomically(f, std::span<const std::uint8_t>(big));
        FAIL() << "a short write passed";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), f.string());
        EXPECT_NE(e.reason().find("cannot write: "), std::string::npos) << e.reason();
        EXPECT_NE(e.reason().find(std::strerror(EFBIG)), std::string::npos) << e.reason();  // the system's reason
    }
    EXPECT_EQ(read_text(f), "the good one");
    EXPECT_EQ(s.entries(), 1u);
}

TEST(FileSet, CommitsEveryFileTogether) {
    Scratch s;
    write_file_atomically(s.dir / "scene.gltf", std::string_view("old gltf"));
    write_file_atomically(s.dir / "scene.bin", std::string_view("old bin"));
    {
        FileSet set;
        set.stage(s.dir / "scene_image0.png", std::string_view("png"));
        set.stage(s.dir / "scene.bin", std::string_view("new bin"));
        EXPECT_TRUE(set.staged(s.dir / "." / "scene.bin"));  // another spelling of one file
        EXPECT_THROW(set.stage(s.dir / "sub" / ".." / "scene.bin", std::string_view("again")), Error);
        set.stage(s.dir / "scene.gltf", std::string_view("new gltf"));
        // Nothing is in place before the commit.
        EXPECT_EQ(read_text(s.dir / "scene.gltf"), "old gltf");
        EXPECT_FALSE(fs::exists(s.dir / "scene_image0.png"));
        set.commit();
    }
    EXPECT_EQ(read_text(s.dir / "scene.gltf"), "new gltf");
    EXPECT_EQ(read_text(s.dir / "scene.bin"), "new bin");
    EXPECT_EQ(read_text(s.dir / "scene_image0.png"), "png");
    EXPECT_EQ(s.entries(), 3u);  // no temporary, no backup
}

TEST(FileSet, ASetNotCommittedChangesNothing) {
    Scratch s;
    write_file_atomically(s.dir / "a.obj", std::string_view("old obj"));
    {
        FileSet set;
        set.stage(s.dir / "a.mtl", std::string_view("new mtl"));
        set.stage(s.dir / "a.obj", std::string_view("new obj"));
    }  // an error between stage and commit: the set goes out of scope
    EXPECT_EQ(read_text(s.dir / "a.obj"), "old obj");
    EXPECT_EQ(s.entries(), 1u);
}

TEST(FileSet, AFailedStageNamesTheDestinationAndLeavesNoTemporary) {
    Scratch s;
    write_file_atomically(s.dir / "a.gltf", std::string_view("old"));
    FileSet set;
    set.stage(s.dir / "a.bin", std::string_view("bin"));
    const std::vector<std::uint8_t> big(64 * 1024, 1);
    try {
        FileSizeLimit limit(4096);
        set.stage(s.dir / "a_image0.png", std::span<const std::uint8_t>(big));
        FAIL() << "a short write passed";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), (s.dir / "a_image0.png").string());
        EXPECT_NE(e.reason().find(std::strerror(EFBIG)), std::string::npos) << e.reason();
    }
    EXPECT_THROW(set.stage(s.dir, std::string_view("a folder")), Error);  // a folder is never replaced
    EXPECT_EQ(s.entries(), 2u);  // a.gltf and the staged a.bin's temporary
    EXPECT_EQ(read_text(s.dir / "a.gltf"), "old");
}

TEST(FileSet, AMoveThatFailsRestoresTheFilesAlreadyMoved) {
    Scratch s;
    write_file_atomically(s.dir / "one.txt", std::string_view("old one"));
    fs::create_directories(s.dir / "sub");
    {
        FileSet set;
        set.stage(s.dir / "one.txt", std::string_view("new one"));
        set.stage(s.dir / "sub" / "two.txt", std::string_view("new two"));
        fs::remove_all(s.dir / "sub");  // the second move cannot happen
        try {
            set.commit();
            FAIL() << "no error";
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), (s.dir / "sub" / "two.txt").string());
        }
    }
    EXPECT_EQ(read_text(s.dir / "one.txt"), "old one");
    EXPECT_EQ(s.entries(), 1u);
}

TEST(FileSet, TemporariesOfAKilledProcessAreRemoved) {
    Scratch s;
    // Names as this process makes them (".out.partial-PID-THREAD-HOST.png"), with other PIDs.
    const std::string ours = temporary_path_beside(s.dir / "out.png").filename().string();
    const std::string host = ours.substr(ours.rfind('-') + 1, ours.rfind('.') - ours.rfind('-') - 1);
    ASSERT_EQ(host.size(), 8u) << ours;
    auto named = [&](const std::string& stem_kind, long pid, const std::string& on) {
        return s.dir / (stem_kind + std::to_string(pid) + "-1-" + on + ".png");
    };
    const long dead = dead_pid();
    const fs::path stale = named(".out.partial-", dead, host);
    const fs::path stale_backup = named(".out.previous-", dead, host);
    const fs::path live = named(".out.partial-", long(::getpid()), host);
    const fs::path other = named(".other.partial-", dead, host);
    const fs::path user = s.dir / ".out.partial-notes.png";  // not one of ours
    const fs::path elsewhere = named(".out.partial-", dead, host == "00000000" ? "00000001" : "00000000");  // another machine's
    for (const auto& p : {stale, stale_backup, live, other, user, elsewhere}) std::ofstream(p) << "x";
    FileSet set;
    set.stage(s.dir / "out.png", std::string_view("png"));
    set.commit();
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_FALSE(fs::exists(stale_backup));
    EXPECT_TRUE(fs::exists(live));   // a running process's
    EXPECT_TRUE(fs::exists(other));  // another destination's: left for its own writer
    EXPECT_TRUE(fs::exists(user));
    EXPECT_TRUE(fs::exists(elsewhere));
    EXPECT_EQ(remove_stale_temporaries_in(s.dir), 1u);  // the whole folder: `other`
    EXPECT_FALSE(fs::exists(other));
}
