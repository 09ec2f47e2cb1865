// The flags of a Job (apps/fresnel/job_options.h) and the way back: a Job written as a
// `fresnel render` command line (the viewer's "copy as command line") parses back, through
// the very flags `render` declares, to the same Job; and every key of the settings registry
// through every front end that offers it (flags, scene files, view scripts, the web page's
// set). No GL.
#include "command_line.h"
#include "job_options.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "fresnel/job/orbit_controller.h"
#include "fresnel/job/scene_document.h"
#include "fresnel/job/settings.h"
#include "fresnel/viewer/script.h"

using namespace fresnel;
using namespace fresnel::cli;
namespace fs = std::filesystem;

namespace {

// Parses `line` ("fresnel render MODEL -o OUT ...") with render's flags.
Job parse(const std::string& line) {
    CLI::App app{"test"};
    auto flags = std::make_shared<RenderOptions>();
    std::string output;
    CLI::App* cmd = app.add_subcommand("render");
    cmd->add_option("model", flags->models);
    cmd->add_option("-o,--output", output)->required();
    add_job_flags(cmd, *flags);
    const std::string prefix = "fresnel ";
    EXPECT_EQ(line.rfind(prefix, 0), 0u) << line;
    app.parse(line.substr(prefix.size()), false);
    std::optional<Job> job = job_from_options(*flags, Job{});
    EXPECT_TRUE(job) << line;
    if (job && !flags->models.empty()) job->source.model = flags->models.front();
    return job.value_or(Job{});
}

}  // namespace

TEST(JobFlags, DefaultJobIsTheShortestLine) {
    Job job;
    EXPECT_EQ(render_command_line(job, "out.png"), "fresnel render -o out.png --yaw 0 --pitch 0");
    EXPECT_EQ(parse(render_command_line(job, "out.png")), job);
}

TEST(JobFlags, EveryFieldRoundTrips) {
    Job job;
    job.source.model = "/models/my helmet.glb";  // needs quoting
    job.source.scene = 1;
    job.source.allow_external_files = true;
    job.source.pose_skins = true;
    // A camera as the viewer leaves it: orbited, panned, dollied (numbers with many digits).
    OrbitViewport view{Bounds{{-1, -1, -1}, {1, 2, 1}, false}, 1280, 720};
    job.camera = dolly(pan(orbit(job.camera, 123.0f, -47.0f), view, 31.0f, 17.0f), view, 0.7f);
    job.camera.yfov_deg = 38.5f;
    job.environment.kind = Job::Environment::Kind::File;
    job.environment.path = "/envs/sky.hdr";
    job.environment.rotation_deg = 33.3f;
    job.environment.intensity = 0.7f;
    job.environment.bake_samples = 64;
    job.environment.bake_size = 128;
    job.environment.use_cache = false;
    job.background.mode = Job::Background::Mode::Color;
    job.background.color = {0.1f, 0.2f, 0.3f};
    job.output.width = 1280;
    job.output.height = 720;
    job.output.msaa = 2;
    job.output.anisotropy = 4;
    job.output.tone_mapper = ToneMapper::AcesHill;
    job.output.exposure_ev = -1.25f;
    job.output.encoding = Encoding::Gamma22;
    job.output.debug = DebugChannel::Roughness;
    job.output.energy_compensation = false;
    job.output.brdf = *fresnel::brdf::parse_brdf_model("D=beckmann,G=kelemen,F=exact:gold,diffuse=oren-nayar");
    job.lights.scene_lights = false;
    std::string line = render_command_line(job, "view.png");
    EXPECT_NE(line.find("'/models/my helmet.glb'"), std::string::npos) << line;
    Job back = parse(line);
    EXPECT_EQ(back, job) << line;
    EXPECT_EQ(back.camera, job.camera) << line;

    // The other environment and background forms (fields a form does not use at their defaults).
    job.environment.path.clear();
    job.environment.kind = Job::Environment::Kind::Color;
    job.environment.color = {0.5f, 0.25f, 1.0f};
    job.background.mode = Job::Background::Mode::Blurred;
    job.background.color = glm::vec3(0.0f);
    EXPECT_EQ(parse(render_command_line(job, "a.png")), job);
    job.environment.kind = Job::Environment::Kind::None;
    job.environment.color = glm::vec3(1.0f);
    job.background.mode = Job::Background::Mode::Transparent;
    EXPECT_EQ(parse(render_command_line(job, "a.png")), job);
    job.environment.kind = Job::Environment::Kind::Studio;
    job.camera = Job::Camera{};
    job.camera.scene_camera = 2;
    EXPECT_EQ(parse(render_command_line(job, "a.png")), job);
}

TEST(JobFlags, LightsRoundTripWithinRounding) {
    Job job;
    job.lights.extra = {parse_light("dir:30,45,3"), parse_light("dir:-120,15,1,0.85,0.9,1"),
                        parse_light("point:1,2,-3,40,1,0.5,0.25")};
    Job back = parse(render_command_line(job, "a.png"));
    ASSERT_EQ(back.lights.extra.size(), job.lights.extra.size());
    for (std::size_t i = 0; i < job.lights.extra.size(); ++i) {
        const LightInstance &a = job.lights.extra[i], &b = back.lights.extra[i];
        EXPECT_EQ(a.type, b.type);
        EXPECT_LT(glm::length(a.direction - b.direction), 1e-5f) << i;
        EXPECT_LT(glm::length(a.position - b.position), 1e-5f) << i;
        EXPECT_LT(glm::length(a.radiance - b.radiance), 1e-5f) << i;
    }
}

TEST(JobFlags, ShellQuoting) {
    EXPECT_EQ(shell_quote("a/b.glb"), "a/b.glb");
    EXPECT_EQ(shell_quote("a b"), "'a b'");
    EXPECT_EQ(shell_quote("it's"), "'it'\\''s'");
    EXPECT_EQ(shell_quote(""), "''");
}

// --- the settings registry (fresnel/job/settings.h) through every front end ---------------

namespace {

// A scene file document of `job` read back onto the default job.
Job through_scene_file(const Job& job) {
    Diagnostics diag;
    nlohmann::json doc = scene_document(job, ".");
    SceneFile sf = parse_scene_document(doc, "roundtrip.fresnel.json", ".", Job{}, diag);
    EXPECT_EQ(diag.total(), 0u) << doc.dump() << "\n" << (diag.lines().empty() ? "" : diag.lines().front());
    return sf.job;
}

// `set KEY VALUE` as a view script line, read as `fresnel view --script` reads it and applied
// as the viewer applies it (settings::set on its job).
Job through_view_script(const std::string& key, const std::string& value) {
    fs::path path = fs::temp_directory_path() / ("fresnel-settings-" + std::to_string(::getpid()) + ".txt");
    std::ofstream(path) << "# round trip\nset " << key << " " << value << "\n";
    std::vector<viewer::Command> commands = viewer::read_view_script(path.string());
    fs::remove(path);
    EXPECT_EQ(commands.size(), 1u);
    Job job;
    if (commands.size() == 1) {
        EXPECT_EQ(commands[0].name, "set");
        settings::set(job, commands[0].args.at(0), commands[0].args.at(1), path.string());
    }
    return job;
}

}  // namespace

// Every key of the registry, at a value other than its default: its flag parses to a Job
// holding it, the print-back parses to the same Job, a scene file written from the Job reads
// back to it, the view script's `set KEY VALUE` of the scene file's value gives it again, and
// so does the web page's fresnel_set(KEY, VALUE) (settings::set by key; its browser test
// drives the page itself).
TEST(SettingsRegistry, EveryKeyRoundTripsThroughEveryFrontEnd) {
    int cli = 0, file = 0, script = 0, web = 0;
    for (const settings::Setting& s : settings::all()) {
        SCOPED_TRACE(s.key);
        const std::string example = settings::example(s);
        const std::string want = settings::format(s, settings::parse(s, example, "test"));
        ASSERT_NE(want, settings::default_text(s)) << "the example is the default";
        // 1. The command line.
        Job job;
        if (s.offered(settings::kCli) && !s.flag.empty()) {
            std::string line = "fresnel render -o a.png ";
            if (s.type != settings::Type::Bool) line += s.flag + " " + shell_quote(example);
            else if ((want == "false") == s.negated_flag) line += s.flag;
            else FAIL() << "a switch that cannot set " << want;
            job = parse(line);
            ++cli;
            EXPECT_EQ(parse(render_command_line(job, "a.png")), job) << render_command_line(job, "a.png");
        } else {
            settings::set(job, s, example, "test");
        }
        EXPECT_EQ(settings::get(job, s), want);
        // 2. A scene file.
        if (s.offered(settings::kSceneFile)) {
            Job back = through_scene_file(job);
            EXPECT_EQ(back, job);
            EXPECT_EQ(settings::get(back, s), want);
            ++file;
        }
        // 3. A view script.
        if (s.offered(settings::kViewScript)) {
            Job back = through_view_script(s.key, settings::get(job, s));
            EXPECT_EQ(settings::get(back, s), want);
            ++script;
        }
        // 4. The web page's fresnel_set: by key, and by the flag's name the page's URL uses.
        if (s.offered(settings::kWeb)) {
            Job by_key, by_flag;
            settings::set(by_key, s.key, settings::get(job, s), "fresnel_set");
            EXPECT_EQ(settings::get(by_key, s), want);
            if (!s.flag.empty() && s.type != settings::Type::Bool) {
                settings::set(by_flag, s.flag.substr(2), example, "fresnel_set");
                EXPECT_EQ(settings::get(by_flag, s), want);
            }
            ++web;
        }
    }
    std::printf("round trips: %d flags, %d scene-file keys, %d view-script keys, %d web keys\n", cli, file, script, web);
    EXPECT_GE(cli, 30);
    EXPECT_GE(file, 25);
}

// One error format for a bad value, whichever front end reads it: "expected <what the
// setting takes>, got '<text>'", named by the flag, the file and JSON pointer, or the
// script's file and line.
TEST(SettingsRegistry, BadValuesGetOneMessageEverywhere) {
    const settings::Setting& pitch = settings::at("camera.pitch");
    const std::string reason = "expected a number in [-90, 90] (degrees), got '100'";
    try {
        settings::parse(pitch, "100", "--pitch");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "--pitch: " + reason);
    }
    Diagnostics diag;
    try {
        parse_scene_document(nlohmann::json::parse(R"({"fresnel": 1, "camera": {"pitch": 100}})"), "s.fresnel.json", ".",
                             Job{}, diag);
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "s.fresnel.json");
        EXPECT_EQ(e.where(), "/camera/pitch");
        EXPECT_EQ(e.reason(), reason);
    }
    fs::path path = fs::temp_directory_path() / ("fresnel-bad-" + std::to_string(::getpid()) + ".txt");
    std::ofstream(path) << "set camera.pitch 100\n";
    try {
        viewer::read_view_script(path.string());
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), "line 1");
        EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
    fs::remove(path);
    // Unknown names: the registry's own message.
    Job job;
    EXPECT_THROW(settings::set(job, "camera.yawn", "1", "fresnel_set"), Error);
}

// Old spellings keep working and warn, naming the new key; the registry's texts are its own.
TEST(SettingsRegistry, OldNamesWarnAndDriftsAreGone) {
    Job job;
    Diagnostics diag;
    settings::set(job, "scene-lights", "0", "fresnel_set", &diag);
    EXPECT_FALSE(job.lights.scene_lights);
    ASSERT_EQ(diag.total(), 1u);
    EXPECT_NE(diag.lines().front().find("sceneLights"), std::string::npos) << diag.lines().front();
    // The background's automatic is one word everywhere (auto and env are accepted aliases).
    settings::set(job, "background", "auto", "t");
    EXPECT_EQ(settings::get(job, "background"), "automatic");
    settings::set(job, "background", "env", "t");
    EXPECT_EQ(settings::get(job, "background"), "environment");
    // --env none and automatic are no longer file names.
    settings::set(job, "environment", "none", "t");
    EXPECT_EQ(job.environment.kind, Job::Environment::Kind::None);
    settings::set(job, "environment", "automatic", "t");
    EXPECT_EQ(job.environment.kind, Job::Environment::Kind::Automatic);
    EXPECT_THROW(settings::set(job, "environment", "", "t"), Error);  // was the studio
    // Ranges are the registry's: a negative intensity, an out-of-range colour, a huge MSAA.
    EXPECT_THROW(settings::set(job, "environment.intensity", "-1", "t"), Error);
    EXPECT_THROW(settings::set(job, "background", "2,0,0", "t"), Error);
    EXPECT_THROW(settings::set(job, "render.msaa", "64", "t"), Error);
    EXPECT_THROW(settings::set(job, "render.size", "10x10junk", "t"), Error);
    EXPECT_THROW(settings::set(job, "environment.bakeSize", "100", "t"), Error);  // a power of two
    // The exact-conductor BRDF spelling the schema once refused.
    settings::set(job, "render.brdf", "F=exact:gold", "t");
    EXPECT_FALSE(job.output.brdf.is_default());
    // Scene files now hold the legacy settings the print-back and the file dropped.
    job = Job{};
    settings::set(job, "render.ambient", "0.1,0.2,0.3", "t");
    settings::set(job, "render.fog", "exp2:0.5", "t");
    settings::set(job, "render.fogColor", "0.5,0.5,0.5", "t");
    EXPECT_EQ(through_scene_file(job), job);
    EXPECT_NE(render_command_line(job, "a.png").find("--fog exp2:0.5"), std::string::npos);
}

// The lighting cache key: one function, the same for equal jobs, different when the bake differs.
TEST(SettingsRegistry, OneLightingKey) {
    ResolvedJob a;
    a.environment = ibl::EnvironmentSource{};
    ResolvedJob b = a;
    EXPECT_EQ(lighting_key(a), lighting_key(b));
    b.bake_options.samples = 64;
    EXPECT_NE(lighting_key(a), lighting_key(b));
    ResolvedJob none;
    EXPECT_EQ(lighting_key(none), "none");
    none.needs_brdf_lut = true;
    EXPECT_NE(lighting_key(none), "none");
}
