// The flags of a Job (apps/fresnel/job_options.h) and the way back: a Job written as a
// `fresnel render` command line (the viewer's "copy as command line") parses back, through
// the very flags `render` declares, to the same Job. No GL.
#include "command_line.h"
#include "job_options.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "fresnel/job/orbit_controller.h"

using namespace fresnel;
using namespace fresnel::cli;

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
