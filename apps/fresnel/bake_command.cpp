// `fresnel bake ENV -o DIR`: image-based-lighting precomputation to files
// (KTX2 cube maps, SH coefficients, the BRDF table, EXR previews, a manifest).
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "commands.h"
#include "fresnel/ibl/bake.h"
#include "progress.h"

namespace fresnel::cli {
namespace {

struct BakeCommandOptions {
    std::string env;
    std::string output;
    ibl::BakeOptions bake;
    bool no_previews = false;
    bool json = false;
};

int run_bake(const BakeCommandOptions& o) {
    auto start = std::chrono::steady_clock::now();
    ibl::EnvironmentSource source = ibl::parse_environment(o.env);
    ImageF panorama = ibl::load_panorama(source);
    double load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ProgressBar bar("baking " + source.describe());
    ibl::BakedIbl baked = ibl::bake(panorama, o.bake, [&](double f) { bar.update(f); });
    bar.finish();
    baked.source = source.describe();
    ibl::save_baked(baked, o.output, o.bake, !o.no_previews);
    double total_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (o.json) {
        nlohmann::json j = {{"output", o.output}, {"source", baked.source}, {"key", baked.key},
                            {"panorama", {panorama.width, panorama.height}}, {"load_ms", load_ms},
                            {"bake_ms", baked.bake_ms}, {"total_ms", total_ms},
                            {"breakdown_ms", {{"cube", baked.cube_ms}, {"specular", baked.specular_ms},
                                              {"irradiance", baked.irradiance_ms}, {"lut", baked.lut_ms}}}};
        std::printf("%s\n", j.dump().c_str());
    } else {
        std::printf("baked %s (%dx%d) into %s: %.0f ms bake, %.0f ms total\n", baked.source.c_str(), panorama.width,
                    panorama.height, o.output.c_str(), baked.bake_ms, total_ms);
    }
    return kExitOk;
}

}  // namespace

Runner add_bake_command(CLI::App& app) {
    auto o = std::make_shared<BakeCommandOptions>();
    CLI::App* cmd = app.add_subcommand("bake", "Precompute image-based lighting of an environment into a folder");
    cmd->footer("Examples:\n"
                "  fresnel bake sky.hdr -o sky.ibl                # then: fresnel render model.glb --env sky.ibl\n");
    cmd->add_option("env", o->env, "Equirectangular .hdr/.exr, color:R,G,B or studio")->required();
    cmd->add_option("-o,--output", o->output, "Output folder (created)")->required();
    cmd->add_option("--size", o->bake.size, "Specular cube face size, power of two")->capture_default_str();
    cmd->add_option("--levels", o->bake.levels, "Specular mip levels (roughness k/(levels-1))")->capture_default_str();
    cmd->add_option("--samples", o->bake.samples, "GGX samples per texel")->capture_default_str()
        ->check(CLI::Range(1, 65536));
    cmd->add_option("--lut-size", o->bake.lut_size, "BRDF table size")->capture_default_str()->check(CLI::Range(2, 4096));
    cmd->add_option("--lut-samples", o->bake.lut_samples, "Samples per BRDF table entry")->capture_default_str()
        ->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--irradiance-size", o->bake.irradiance_size, "Face size of the irradiance cube written")
        ->capture_default_str()->check(CLI::Range(1, 1024));
    cmd->add_option("--threads", o->bake.threads, "Worker threads (0 = all cores)")->capture_default_str();
    cmd->add_flag("--no-previews", o->no_previews, "Do not write the EXR previews");
    cmd->add_flag("--json", o->json, "Print timings as one JSON line");
    return [o] { return run_bake(*o); };
}

}  // namespace fresnel::cli
