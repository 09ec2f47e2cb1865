// `fresnel compare A B [--mask auto|FILE] [--json] [--heatmap OUT.png]`: how far image A (under
// test) is from image B (the reference): PSNR, SSIM, LDR-FLIP (and HDR-FLIP when both are
// linear EXR/HDR files) and model-viewer's RMS in dB, over every pixel or over an object mask.
// The metrics live in fresnel/core/metrics.h; this file loads, masks, prints and draws.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_common.h"
#include "commands.h"
#include "fresnel/core/heatmap.h"
#include "fresnel/core/image.h"
#include "fresnel/core/metrics.h"

namespace fresnel::cli {

namespace {

namespace fs = std::filesystem;

struct CompareOptions {
    std::string test, reference;
    std::string mask;  // empty: every pixel; "auto"; or a mask image
    std::string heatmap;
    double ppd = flip_default_pixels_per_degree();
    bool json = false;
};

struct Loaded {
    ImageF display;  // display-encoded RGBA in [0,1]
    ImageF linear;   // the file's values, for EXR/HDR only (empty otherwise)
    bool is_float = false;
};

// PNG (and the other 8-bit formats) hold display values; EXR and Radiance HDR hold linear ones.
Loaded load(const std::string& path) {
    const ImageLimits limits;
    auto bytes = read_file_bytes(path, limits.max_decoded_bytes);
    Loaded l;
    l.is_float = is_linear_image(bytes);
    ImageF img = decode_image_float(bytes, path, limits);
    if (l.is_float) {
        l.display = to_display(img);
        l.linear = std::move(img);
    } else {
        l.display = std::move(img);
    }
    return l;
}

std::string size_text(const ImageF& i) { return std::to_string(i.width) + "x" + std::to_string(i.height); }

// compare.py's conventions for identical images (PSNR 99 dB, RMS -99 dB); NaN -> null.
nlohmann::json number(double v) {
    if (std::isnan(v)) return nullptr;
    if (std::isinf(v)) return v > 0 ? 99.0 : -99.0;
    return v;
}

std::string text(double v, const char* fmt, const char* unit = "") {
    if (std::isnan(v)) return "n/a";
    if (std::isinf(v)) return std::string(v > 0 ? "inf" : "-inf") + unit;
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf + std::string(unit);
}

int run_compare(const CompareOptions& o) {
    if (!o.heatmap.empty() && fs::path(o.heatmap).extension() != ".png") {
        print_error("--heatmap: " + o.heatmap + ": the heat map is written as PNG (.png)");
        return kExitUsage;
    }
    Loaded test = load(o.test), ref = load(o.reference);
    if (test.display.width != ref.display.width || test.display.height != ref.display.height)
        throw Error(o.test, "", "image is " + size_text(test.display) + ", but " + o.reference + " is " +
                                    size_text(ref.display) + ": compare needs images of one size");
    const int w = ref.display.width, h = ref.display.height;
    const std::size_t total = std::size_t(w) * h;

    PixelMask mask;
    std::string mask_name = "none";
    if (o.mask == "auto") {
        mask = background_mask(test.display, ref.display);
        mask_name = "auto";
    } else if (!o.mask.empty()) {
        Loaded m = load(o.mask);
        if (m.display.width != w || m.display.height != h)
            throw Error(o.mask, "", "mask is " + size_text(m.display) + ", but " + o.test + " and " + o.reference +
                                        " are " + size_text(ref.display));
        mask = mask_from_image(m.is_float ? m.linear : m.display);
        mask_name = o.mask;
    }
    const std::size_t pixels = mask_count(mask, total);
    const bool empty = pixels == 0;  // both images are background everywhere: identical, as compare.py says

    const double psnr = empty ? INFINITY : psnr_db(test.display, ref.display, mask);
    const SsimResult s = empty ? SsimResult{1.0, 0} : ssim(test.display, ref.display, mask);
    const double mv = empty ? -INFINITY : mv_rms_db(test.display, ref.display, mask);
    std::vector<float> ldr = flip_ldr(ref.display, test.display, o.ppd);
    const double flip_mean = empty ? 0.0 : masked_mean(ldr, mask);
    const bool hdr = test.is_float && ref.is_float;
    std::vector<float> hdr_map;
    FlipExposures exposures;
    double hdr_mean = NAN;
    if (hdr) {
        exposures = flip_exposures(ref.linear);
        hdr_map = flip_hdr(ref.linear, test.linear, exposures, o.ppd);
        hdr_mean = empty ? 0.0 : masked_mean(hdr_map, mask);
    }

    if (!o.heatmap.empty()) {
        char caption[64];
        std::snprintf(caption, sizeof caption, "%s-FLIP MEAN %.4f", hdr ? "HDR" : "LDR", hdr ? hdr_mean : flip_mean);
        write_png(o.heatmap, error_heatmap(hdr ? hdr_map : ldr, w, h, caption));
    }

    if (o.json) {
        nlohmann::json j;
        j["test"] = o.test;
        j["reference"] = o.reference;
        j["width"] = w;
        j["height"] = h;
        j["mask"] = mask_name;
        j["pixels"] = pixels;
        j["total_pixels"] = total;
        j["psnr_db"] = number(psnr);
        j["ssim"] = number(s.ssim);
        j["ssim_pixels"] = s.pixels;
        j["flip"] = number(flip_mean);
        j["flip_pixels_per_degree"] = o.ppd;
        if (hdr) {
            j["hdr_flip"] = number(hdr_mean);
            j["hdr_flip_exposures"] = {{"start", exposures.start}, {"stop", exposures.stop}, {"count", exposures.count}};
        } else {
            j["hdr_flip"] = nullptr;
        }
        j["mv_rms_db"] = number(mv);
        if (!o.heatmap.empty()) j["heatmap"] = o.heatmap;
        std::printf("%s\n", j.dump(2).c_str());
        return kExitOk;
    }
    std::printf("%s (test) vs %s (reference), %dx%d\n", o.test.c_str(), o.reference.c_str(), w, h);
    std::printf("  %-10s %s: %zu of %zu pixels\n", "mask", mask_name.c_str(), pixels, total);
    std::printf("  %-10s %s\n", "PSNR", text(psnr, "%.2f", " dB").c_str());
    std::printf("  %-10s %s (%zu pixels with the whole 11x11 window inside the image)\n", "SSIM",
                text(s.ssim, "%.4f").c_str(), s.pixels);
    std::printf("  %-10s %s (mean, %.1f pixels per degree)\n", "LDR-FLIP", text(flip_mean, "%.4f").c_str(), o.ppd);
    if (hdr)
        std::printf("  %-10s %s (mean, %d exposures from %.2f to %.2f stops)\n", "HDR-FLIP", text(hdr_mean, "%.4f").c_str(),
                    exposures.count, exposures.start, exposures.stop);
    std::printf("  %-10s %s (model-viewer's score; it fails above -22 dB)\n", "RMS", text(mv, "%.2f", " dB").c_str());
    if (!o.heatmap.empty()) std::printf("  %-10s %s\n", "heat map", o.heatmap.c_str());
    return kExitOk;
}

}  // namespace

Runner add_compare_command(CLI::App& app) {
    auto o = std::make_shared<CompareOptions>();
    CLI::App* cmd = app.add_subcommand(
        "compare", "Measure how far image A is from reference B: PSNR, SSIM, FLIP, model-viewer's RMS");
    cmd->footer("Examples:\n"
                "  fresnel compare test.png ref.png                           # PSNR, SSIM, FLIP\n"
                "  fresnel compare test.exr ref.exr --heatmap diff.png --json\n");
    cmd->add_option("a", o->test, "Image under test: .png (display-encoded), .exr/.hdr (linear)")->required();
    cmd->add_option("b", o->reference, "Reference image, the same size")->required();
    cmd->add_option("--mask", o->mask,
                    "Compare only some pixels: auto (where either image is not black or transparent, as "
                    "compare.py) or a mask image (pixels with max(R,G,B) x alpha >= 0.5). Default: every pixel");
    cmd->add_flag("--json", o->json, "Print a JSON object (every metric and pixel counts) instead of a table");
    cmd->add_option("--heatmap", o->heatmap,
                    "Write the FLIP error map (HDR-FLIP for two EXR/HDR files) in magma, with a legend, to this PNG");
    cmd->add_option("--ppd", o->ppd, "FLIP's observer: pixels per degree of visual angle (default 67.0: 0.7 m from a 0.7 m wide 4K display)")
        ->check(CLI::Range(0.1, 1000.0));
    return [o] { return run_compare(*o); };
}

}  // namespace fresnel::cli
