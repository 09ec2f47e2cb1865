// Image tests: the shared glTF models rendered through fresnel::Renderer on the
// headless context (llvmpipe in CI), checked with metrics and tolerances, never
// exact bytes. Every test skips when ${FRESNEL_SHARED_DIR} is absent.
//
// Set FRESNEL_TEST_IMAGE_DIR to a folder to have the rendered images written there as PNG.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "fresnel/core/color.h"
#include "fresnel/core/error.h"
#include "fresnel/core/image.h"
#include "fresnel/core/metrics.h"
#include "fresnel/gpu/context.h"
#include "fresnel/ibl/bake.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/job/camera.h"
#include "fresnel/job/lights.h"
#include "fresnel/render/renderer.h"
#include "fresnel/scene/gltf_loader.h"
#include "fresnel/scene/scene.h"

namespace fs = std::filesystem;
using namespace fresnel;

namespace {

// ---------------------------------------------------------------------------
// Shared folder and model discovery.

const fs::path kSharedDir = FRESNEL_SHARED_DIR;
fs::path models_dir() { return kSharedDir / "assets" / "models"; }

#define REQUIRE_SHARED_MODELS()                                                                            \
    do {                                                                                                   \
        if (!fs::is_directory(models_dir()))                                                               \
            GTEST_SKIP() << "shared assets not found: " << models_dir().string()                          \
                         << " does not exist (FRESNEL_SHARED_DIR); image tests need ../shared";           \
    } while (0)

// The model file of a sample-model folder: a .glb or .gltf at the top, else in the
// Khronos layout's glTF-Binary/, glTF/ or glTF-Embedded/ subfolders. A file named
// like the folder wins over others (variants live in other subfolders).
fs::path main_model_file(const fs::path& folder) {
    for (const char* sub : {"", "glTF-Binary", "glTF", "glTF-Embedded"}) {
        fs::path dir = *sub ? folder / sub : folder;
        std::error_code ec;
        if (!fs::is_directory(dir, ec)) continue;
        std::vector<fs::path> found;
        for (const auto& e : fs::directory_iterator(dir, ec)) {
            if (!e.is_regular_file()) continue;
            std::string ext = e.path().extension().string();
            for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
            if (ext == ".glb" || ext == ".gltf") found.push_back(e.path());
        }
        if (found.empty()) continue;
        std::sort(found.begin(), found.end(), [&](const fs::path& a, const fs::path& b) {
            auto rank = [&](const fs::path& p) {
                return (p.stem() == folder.filename() ? 0 : 2) + (p.extension() == ".glb" ? 0 : 1);
            };
            return std::make_pair(rank(a), a.string()) < std::make_pair(rank(b), b.string());
        });
        return found.front();
    }
    return {};
}

std::vector<std::string> model_folders() {
    std::vector<std::string> out;
    std::error_code ec;
    if (fs::is_directory(models_dir(), ec))
        for (const auto& e : fs::directory_iterator(models_dir(), ec))
            if (e.is_directory()) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

// ---------------------------------------------------------------------------
// One headless context for the whole binary (created on first use).

class GpuEnvironment : public ::testing::Environment {
public:
    void TearDown() override { context_.reset(); }
    static gpu::Context* context() {
        if (!context_ && error_.empty()) {
            try {
                context_ = gpu::create_headless_context();
            } catch (const std::exception& e) {
                error_ = e.what();
            }
        }
        if (context_) context_->make_current();
        return context_.get();
    }
    static const std::string& error() { return error_; }

private:
    static inline std::unique_ptr<gpu::Context> context_;
    static inline std::string error_;
};
[[maybe_unused]] ::testing::Environment* const kGpuEnvironment =
    ::testing::AddGlobalTestEnvironment(new GpuEnvironment);

#define REQUIRE_CONTEXT()                                                                               \
    gpu::Context* context = GpuEnvironment::context();                                                  \
    ASSERT_NE(context, nullptr) << "no headless OpenGL context (EGL/llvmpipe): " << GpuEnvironment::error()

// ---------------------------------------------------------------------------
// Rendering.

Scene load_model(const fs::path& path) {
    Diagnostics diag;
    return load_gltf(path, diag);
}

struct View {
    float yaw = 0, pitch = 0;
};

struct Frame {
    ImageF image;
    FrameStats stats;
    CameraSetup camera;
};

RenderSettings settings_of_size(int w, int h) {
    RenderSettings s;
    s.width = w;
    s.height = h;
    s.msaa = 4;
    return s;
}

// Renders like the CLI: orbit camera around the scene bounds, the scene's lights,
// the default pair when it has none; with `punctual_lights` false, none at all (as
// `--env X --no-scene-lights`: the environment in settings lights the scene alone).
Frame render(gpu::Context& context, const Scene& scene, View view, const RenderSettings& settings,
             bool punctual_lights = true) {
    auto instances = flatten(scene);
    OrbitParams op;
    op.yaw_deg = view.yaw;
    op.pitch_deg = view.pitch;
    Frame f;
    f.camera = orbit_camera(scene_bounds(scene, instances), op, settings.width, settings.height);
    std::vector<LightInstance> lights;
    if (punctual_lights) {
        lights = scene_lights(scene, instances);
        if (lights.empty()) lights = default_lights();
    }
    Renderer renderer(context);
    renderer.set_scene(scene);
    f.image = renderer.render(f.camera, lights, settings, &f.stats);
    return f;
}

// Writes the image for a person to look at when FRESNEL_TEST_IMAGE_DIR is set.
void maybe_save(const ImageF& image, const std::string& name) {
    const char* dir = std::getenv("FRESNEL_TEST_IMAGE_DIR");
    if (!dir || !*dir) return;
    std::error_code ec;
    fs::create_directories(dir, ec);
    write_png(fs::path(dir) / (name + ".png"), to_image8(image, false));
}

// ---------------------------------------------------------------------------
// Metrics on display-encoded images.

glm::vec3 rgb(const ImageF& img, int x, int y) {
    const float* p = img.at(x, y);
    return {p[0], p[1], p[2]};
}

std::size_t count_pixels(const ImageF& img, const std::function<bool(glm::vec3)>& pred) {
    std::size_t n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) n += pred(rgb(img, x, y));
    return n;
}

std::size_t count_nonfinite(const ImageF& img) {
    std::size_t n = 0;
    for (float v : img.pixels) n += !std::isfinite(v);
    return n;
}

bool is_magenta(glm::vec3 c) { return c.x > 0.99f && c.y < 0.01f && c.z > 0.99f; }
bool is_strong_red(glm::vec3 c) { return c.x > 0.5f && c.y < 0.25f && c.z < 0.25f; }
bool is_strong_green(glm::vec3 c) { return c.y > 0.5f && c.x < 0.35f && c.z < 0.35f; }

float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
    double ma = 0, mb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
    ma /= double(a.size());
    mb /= double(b.size());
    double sab = 0, saa = 0, sbb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        sab += (a[i] - ma) * (b[i] - mb);
        saa += (a[i] - ma) * (a[i] - ma);
        sbb += (b[i] - mb) * (b[i] - mb);
    }
    return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

// Pixel position (x right, y down, pixel centres at +0.5) of a world point.
glm::vec2 project(const CameraSetup& cam, glm::vec3 p, int w, int h) {
    glm::vec4 c = cam.projection * cam.view * glm::vec4(p, 1.0f);
    glm::vec2 ndc = glm::vec2(c) / c.w;
    return {(ndc.x * 0.5f + 0.5f) * float(w), (0.5f - ndc.y * 0.5f) * float(h)};
}

// The world point on the plane z = plane_z seen through pixel (x, y) (pixel centre).
glm::vec3 unproject_to_plane_z(const CameraSetup& cam, float x, float y, int w, int h, float plane_z) {
    glm::mat4 inv = glm::inverse(cam.projection * cam.view);
    glm::vec2 ndc((x / float(w)) * 2.0f - 1.0f, 1.0f - (y / float(h)) * 2.0f);
    glm::vec4 a = inv * glm::vec4(ndc, -1.0f, 1.0f), b = inv * glm::vec4(ndc, 1.0f, 1.0f);
    glm::vec3 p0 = glm::vec3(a) / a.w, p1 = glm::vec3(b) / b.w;
    float t = (plane_z - p0.z) / (p1.z - p0.z);
    return p0 + t * (p1 - p0);
}

const Node* find_node(const Scene& scene, const std::string& name) {
    for (const auto& n : scene.nodes)
        if (n.name == name) return &n;
    return nullptr;
}

// ---------------------------------------------------------------------------
// Every shared model renders: not blank, finite, no GL errors, no magenta (NaN/Inf marker).

class EveryModel : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryModel, RendersCleanly) {
    REQUIRE_SHARED_MODELS();
    if (GetParam().empty()) GTEST_SKIP() << "no model folders under " << models_dir().string();
    fs::path file = main_model_file(models_dir() / GetParam());
    ASSERT_FALSE(file.empty()) << "no .glb or .gltf in " << (models_dir() / GetParam()).string();
    REQUIRE_CONTEXT();
    Scene scene;
    ASSERT_NO_THROW(scene = load_model(file)) << file.string();

    const int w = 256, h = 256;
    const std::size_t min_covered = std::size_t(w) * h / 100;  // at least 1% of the frame shows the model
    // Two oblique views from above (where the default lights come from): no planar
    // model is seen edge-on.
    for (View view : {View{30, 20}, View{-40, 35}}) {
        SCOPED_TRACE("yaw " + std::to_string(int(view.yaw)) + " pitch " + std::to_string(int(view.pitch)));
        // Display output (what PNGs get): neutral tone map, sRGB, black background.
        Frame f = render(*context, scene, view, settings_of_size(w, h));
        maybe_save(f.image, GetParam() + "_" + std::to_string(int(view.yaw)));
        EXPECT_EQ(f.stats.gl_errors, "");
        EXPECT_GT(f.stats.draw_calls, 0);
        EXPECT_EQ(count_nonfinite(f.image), 0u);
        EXPECT_EQ(count_pixels(f.image, is_magenta), 0u) << "magenta pixels: NaN/Inf reached the frame";
        std::size_t covered =
            count_pixels(f.image, [](glm::vec3 c) { return std::max({c.x, c.y, c.z}) > 3.0f / 255.0f; });
        EXPECT_GE(covered, min_covered) << "the frame is (nearly) blank: " << covered << " pixels differ from the "
                                        << "black background";
        for (float v : f.image.pixels)
            if (!(v >= 0.0f && v <= 1.0f)) {
                ADD_FAILURE() << "display value out of [0,1]: " << v;
                break;
            }

        // Linear float output (what EXR/HDR get): tone-mapped, not encoded, premultiplied.
        RenderSettings linear = settings_of_size(w, h);
        linear.encoding.reset();
        linear.straight_alpha = false;
        Frame g = render(*context, scene, view, linear);
        EXPECT_EQ(g.stats.gl_errors, "");
        EXPECT_EQ(count_nonfinite(g.image), 0u);
        EXPECT_EQ(count_pixels(g.image, is_magenta), 0u) << "magenta pixels in the linear output";
    }
}

std::vector<std::string> model_params() {
    auto m = model_folders();
    if (m.empty()) m.push_back("");  // one skipped instance instead of an uninstantiated suite
    return m;
}

INSTANTIATE_TEST_SUITE_P(SharedModels, EveryModel, ::testing::ValuesIn(model_params()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                             std::string n;
                             for (char c : info.param) n += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                             return n.empty() ? std::string("NoSharedModels") : n;
                         });

// ---------------------------------------------------------------------------
// TextureSettingsTest: samplers (repeat / clamp / mirror), doubleSided. The model
// shows green checks where the renderer is right and red X marks (or solid red)
// where it is wrong.

fs::path model_path(const std::string& folder) { return main_model_file(models_dir() / folder); }

TEST(TextureSettingsTest, FrontShowsGreenChecksAndNoRed) {
    REQUIRE_SHARED_MODELS();
    fs::path file = model_path("TextureSettingsTest");
    if (file.empty()) GTEST_SKIP() << "TextureSettingsTest not in the shared models";
    REQUIRE_CONTEXT();
    Scene scene = load_model(file);
    Frame f = render(*context, scene, View{0, 0}, settings_of_size(256, 256));
    maybe_save(f.image, "TextureSettingsTest_front");
    EXPECT_EQ(f.stats.gl_errors, "");
    std::size_t red = count_pixels(f.image, is_strong_red);
    std::size_t green = count_pixels(f.image, is_strong_green);
    std::printf("TextureSettingsTest: %zu strongly red, %zu strongly green pixels\n", red, green);
    EXPECT_LE(red, 3u) << "red X marks: a sampler wrap mode or doubleSided is handled wrongly";
    EXPECT_GE(green, 400u) << "the green checks and clamp squares are missing";
}

// The same metric on a deliberately broken scene (every sampler clamps, every
// material double-sided) must see the red marks: the check above can fail.
TEST(TextureSettingsTest, MetricSeesRedWhenSettingsAreWrong) {
    REQUIRE_SHARED_MODELS();
    fs::path file = model_path("TextureSettingsTest");
    if (file.empty()) GTEST_SKIP() << "TextureSettingsTest not in the shared models";
    REQUIRE_CONTEXT();
    Scene scene = load_model(file);
    for (auto& t : scene.textures) t.sampler.wrap_s = t.sampler.wrap_t = Wrap::ClampToEdge;
    for (auto& m : scene.materials) m.double_sided = true;
    Frame f = render(*context, scene, View{0, 0}, settings_of_size(256, 256));
    maybe_save(f.image, "TextureSettingsTest_broken");
    std::size_t red = count_pixels(f.image, is_strong_red);
    std::printf("TextureSettingsTest with wrong settings: %zu strongly red pixels\n", red);
    EXPECT_GE(red, 200u);
}

// ---------------------------------------------------------------------------
// TextureCoordinateTest: four textured quads named TopLeft/TopRight/BottomLeft/
// BottomRight (materials of distinct colours), front facing -Z; seen from -Z
// (yaw 180) each must appear in its own corner of the image, and the texture on
// it must be the template's matching corner, not mirrored.

struct Corner {
    const char* name;
    bool left, top;
};
constexpr Corner kCorners[] = {{"TopLeft", true, true}, {"TopRight", false, true},
                               {"BottomLeft", true, false}, {"BottomRight", false, false}};

const Primitive* corner_primitive(const Scene& scene, const std::string& corner) {
    const Node* node = find_node(scene, corner + "Node");
    if (!node || node->mesh < 0 || scene.meshes[std::size_t(node->mesh)].primitives.empty()) return nullptr;
    return &scene.meshes[std::size_t(node->mesh)].primitives[0];
}

// Display-encoded sRGB back to linear.
glm::vec3 linear_of(glm::vec3 display) { return srgb_to_linear(glm::clamp(display, 0.0f, 1.0f)); }

TEST(TextureCoordinateTest, QuadrantsShowTheirCornerMaterial) {
    REQUIRE_SHARED_MODELS();
    fs::path file = model_path("TextureCoordinateTest");
    if (file.empty()) GTEST_SKIP() << "TextureCoordinateTest not in the shared models";
    REQUIRE_CONTEXT();
    Scene scene = load_model(file);

    // The corner materials, by the names the model gives its nodes and materials.
    std::map<std::string, glm::vec3> colour;
    for (const Corner& c : kCorners) {
        const Primitive* p = corner_primitive(scene, c.name);
        ASSERT_NE(p, nullptr) << "no node " << c.name << "Node with a mesh";
        ASSERT_GE(p->material, 0);
        const Material& m = scene.materials[std::size_t(p->material)];
        EXPECT_EQ(m.name, std::string(c.name) + "Material");
        colour[c.name] = glm::normalize(glm::vec3(m.base_color_factor));
    }

    const int w = 512, h = 512;
    Frame f = render(*context, scene, View{180, 0}, settings_of_size(w, h));
    maybe_save(f.image, "TextureCoordinateTest_back_view");
    EXPECT_EQ(f.stats.gl_errors, "");

    // Classify every clearly coloured pixel of each image quadrant by the corner
    // material whose colour direction it is closest to.
    for (const Corner& q : kCorners) {
        std::map<std::string, int> votes;
        int total = 0;
        for (int y = q.top ? 0 : h / 2; y < (q.top ? h / 2 : h); ++y)
            for (int x = q.left ? 0 : w / 2; x < (q.left ? w / 2 : w); ++x) {
                glm::vec3 c = linear_of(rgb(f.image, x, y));
                float mx = std::max({c.x, c.y, c.z}), mn = std::min({c.x, c.y, c.z});
                if (mx < 0.01f || (mx - mn) < 0.5f * mx) continue;  // background, grey back plane, dark print
                glm::vec3 d = glm::normalize(c);
                std::string best;
                float best_cos = -1;
                for (const Corner& k : kCorners) {
                    float cs = glm::dot(d, colour[k.name]);
                    if (cs > best_cos) best_cos = cs, best = k.name;
                }
                if (best_cos > 0.9f) ++votes[best], ++total;
            }
        SCOPED_TRACE(std::string("image quadrant ") + (q.top ? "top " : "bottom ") + (q.left ? "left" : "right"));
        std::string summary;
        for (auto& [k, v] : votes) summary += k + ": " + std::to_string(v) + " ";
        std::printf("TextureCoordinateTest %s%s quadrant: %s\n", q.top ? "top-" : "bottom-", q.left ? "left" : "right",
                    summary.c_str());
        EXPECT_GT(total, w * h / 40) << "too few coloured pixels in the quadrant";
        EXPECT_GE(votes[q.name], int(0.9 * total)) << "quadrant colours: " << summary << "(expected " << q.name
                                                   << "Material)";
    }
}

// The luminance pattern on each quad follows the template texture at the quad's
// texture coordinates (glTF: uv (0,0) = the image's first, top row): it correlates
// with the correctly oriented texture, clearly better than with the texture
// mirrored in u, flipped in v, or both.
TEST(TextureCoordinateTest, TextureIsOrientedAndNotMirrored) {
    REQUIRE_SHARED_MODELS();
    fs::path file = model_path("TextureCoordinateTest");
    if (file.empty()) GTEST_SKIP() << "TextureCoordinateTest not in the shared models";
    REQUIRE_CONTEXT();
    Scene scene = load_model(file);
    const int w = 512, h = 512;
    Frame f = render(*context, scene, View{180, 0}, settings_of_size(w, h));
    EXPECT_EQ(f.stats.gl_errors, "");

    // Nodes of this model have identity transforms (checked), so positions are world positions.
    for (const auto& inst : flatten(scene)) ASSERT_EQ(inst.world, glm::mat4(1.0f));

    for (const Corner& corner : kCorners) {
        SCOPED_TRACE(corner.name);
        const Primitive* p = corner_primitive(scene, corner.name);
        ASSERT_NE(p, nullptr);
        ASSERT_EQ(p->uv0.size(), p->positions.size());
        ASSERT_GE(p->indices.size(), 3u);
        const Material& m = scene.materials[std::size_t(p->material)];
        ASSERT_TRUE(m.base_color.valid());
        const Texture& tex = scene.textures[std::size_t(m.base_color.texture)];
        ASSERT_GE(tex.image, 0);
        const Image8& img = scene.images[std::size_t(tex.image)].pixels;
        ASSERT_GT(img.width, 0);

        // Affine map (x, y) -> uv from the first triangle (the quad is planar, z ~ 0).
        glm::vec3 p0 = p->positions[p->indices[0]], p1 = p->positions[p->indices[1]], p2 = p->positions[p->indices[2]];
        glm::vec2 t0 = p->uv0[p->indices[0]], t1 = p->uv0[p->indices[1]], t2 = p->uv0[p->indices[2]];
        glm::mat2 dp(glm::vec2(p1 - p0), glm::vec2(p2 - p0));
        glm::mat2 dt(t1 - t0, t2 - t0);
        ASSERT_GT(std::fabs(glm::determinant(dp)), 1e-6f);
        glm::mat2 to_uv = dt * glm::inverse(dp);
        auto uv_at = [&](glm::vec2 xy) { return t0 + to_uv * (xy - glm::vec2(p0)); };
        glm::vec3 lo = p->bounds_min, hi = p->bounds_max;
        float plane_z = 0.5f * (lo.z + hi.z);

        // Summed-area table of the texture's linear luminance, for box filtering.
        std::vector<double> sat(std::size_t(img.width + 1) * std::size_t(img.height + 1), 0.0);
        auto S = [&](int x, int y) -> double& { return sat[std::size_t(y) * std::size_t(img.width + 1) + std::size_t(x)]; };
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const std::uint8_t* px = img.at(x, y);
                glm::vec3 c = srgb_to_linear(glm::vec3(px[0], px[1], px[2]) / 255.0f);
                S(x + 1, y + 1) = luminance(c) + S(x, y + 1) + S(x + 1, y) - S(x, y);
            }
        // Mean texture luminance over a box of half-size r texels around uv (repeat wrap, as the sampler).
        auto texture_luma = [&](glm::vec2 uv, float r) {
            float cx = uv.x * float(img.width), cy = uv.y * float(img.height);
            int x0 = int(std::floor(cx - r)), x1 = int(std::ceil(cx + r)), y0 = int(std::floor(cy - r)),
                y1 = int(std::ceil(cy + r));
            x0 = std::clamp(x0, 0, img.width - 1), x1 = std::clamp(x1, x0 + 1, img.width);
            y0 = std::clamp(y0, 0, img.height - 1), y1 = std::clamp(y1, y0 + 1, img.height);
            return (S(x1, y1) - S(x0, y1) - S(x1, y0) + S(x0, y0)) / double((x1 - x0) * (y1 - y0));
        };

        std::vector<double> rendered, expected, mirrored_u, flipped_v, both;
        glm::vec2 inset = 0.03f * glm::vec2(hi - lo);  // stay clear of the quad's antialiased edges
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                glm::vec3 wp = unproject_to_plane_z(f.camera, float(x) + 0.5f, float(y) + 0.5f, w, h, plane_z);
                if (wp.x < lo.x + inset.x || wp.x > hi.x - inset.x || wp.y < lo.y + inset.y || wp.y > hi.y - inset.y)
                    continue;
                glm::vec2 uv = uv_at(glm::vec2(wp));
                glm::vec3 wn = unproject_to_plane_z(f.camera, float(x) + 1.5f, float(y) + 0.5f, w, h, plane_z);
                float footprint = glm::length(uv_at(glm::vec2(wn)) - uv) * float(img.width);
                float r = std::max(0.5f, 0.5f * footprint);
                rendered.push_back(luminance(linear_of(rgb(f.image, x, y))));
                expected.push_back(texture_luma(uv, r));
                mirrored_u.push_back(texture_luma({1.0f - uv.x, uv.y}, r));
                flipped_v.push_back(texture_luma({uv.x, 1.0f - uv.y}, r));
                both.push_back(texture_luma({1.0f - uv.x, 1.0f - uv.y}, r));
            }
        ASSERT_GT(rendered.size(), 2000u) << "the quad covers too few pixels";
        double c_ok = pearson(rendered, expected), c_u = pearson(rendered, mirrored_u),
               c_v = pearson(rendered, flipped_v), c_uv = pearson(rendered, both);
        std::printf("TextureCoordinateTest %-11s correlation with the texture: %.3f (mirrored u %.3f, flipped v %.3f, "
                    "both %.3f) over %zu pixels\n",
                    corner.name, c_ok, c_u, c_v, c_uv, rendered.size());
        // Measured on llvmpipe: 0.99 against <= 0.90 for the alternatives (the template
        // is symmetric but for its corner labels and checker ramps).
        EXPECT_GE(c_ok, 0.95);
        EXPECT_GE(c_ok - std::max({c_u, c_v, c_uv}), 0.05) << "the texture may be mirrored or flipped";
    }
}

// ---------------------------------------------------------------------------
// NormalTangentTest: pairs of tiles in three columns (rough pink, rough blue,
// mirror-smooth gold metal); in each pair the left tile has a real hemisphere, the
// right one a flat tile with a normal map of the same hemisphere. Under the default
// key light (from azimuth 30 = +X side, elevation 45 = above) every hemisphere, real
// or normal-mapped, must be brighter in its upper-right quadrant than in its
// lower-left one, and the normal-mapped one must be shaded like the real one.
// The gold column has roughness 0 (its metallic-roughness texel is (1, 0, 1)): a
// perfect mirror reflects punctual lights in no finite area (D_GGX(alpha = 0) = 0),
// so without image-based lighting it renders black and carries no information here.
//
// Layout (from the model's POSITION data, verified below): tile centres x
// -0.96/-0.64 (pink), -0.16/0.16 (blue), 0.64/0.96 (gold); rows y = 0.8 .. -0.8
// step 0.4; hemisphere radius ~0.1 at z = 0.

struct SphereStats {
    double upper_right = 0, lower_left = 0;
    std::vector<double> patch;  // luminance on a fixed grid around the centre (for correlation)
};

SphereStats sphere_stats(const ImageF& img, glm::vec2 centre, float radius) {
    SphereStats s;
    int n_ur = 0, n_ll = 0;
    for (int y = int(centre.y - radius); y <= int(centre.y + radius); ++y)
        for (int x = int(centre.x - radius); x <= int(centre.x + radius); ++x) {
            if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
            float dx = (float(x) + 0.5f - centre.x) / radius, dy = (float(y) + 0.5f - centre.y) / radius;
            if (dx * dx + dy * dy > 0.8f * 0.8f) continue;
            double l = luminance(rgb(img, x, y));
            if (dx > 0.1f && dy < -0.1f) s.upper_right += l, ++n_ur;  // image y grows downwards
            if (dx < -0.1f && dy > 0.1f) s.lower_left += l, ++n_ll;
        }
    s.upper_right /= std::max(1, n_ur);
    s.lower_left /= std::max(1, n_ll);
    const int grid = 16;
    for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
            float dx = (float(i) + 0.5f) / grid * 2.0f - 1.0f, dy = (float(j) + 0.5f) / grid * 2.0f - 1.0f;
            if (dx * dx + dy * dy > 0.8f * 0.8f) continue;
            int x = int(centre.x + dx * radius), y = int(centre.y + dy * radius);
            s.patch.push_back(luminance(rgb(img, std::clamp(x, 0, img.width - 1), std::clamp(y, 0, img.height - 1))));
        }
    return s;
}

TEST(NormalTangentTest, HemispheresAreLitFromTheKeyLight) {
    REQUIRE_SHARED_MODELS();
    fs::path file = model_path("NormalTangentTest");
    if (file.empty()) GTEST_SKIP() << "NormalTangentTest not in the shared models";
    REQUIRE_CONTEXT();
    Scene scene = load_model(file);
    const float columns[3][2] = {{-0.96f, -0.64f}, {-0.16f, 0.16f}, {0.64f, 0.96f}};
    const char* column_names[3] = {"pink", "blue", "gold"};
    const float rows[5] = {0.8f, 0.4f, 0.0f, -0.4f, -0.8f};
    const float radius = 0.1f;

    // The layout matches the file: a real hemisphere (vertices up to z ~ 0.08) under each left tile centre.
    auto instances = flatten(scene);
    for (const auto& col : columns)
        for (float y : rows) {
            bool found = false;
            for (const auto& inst : instances) {
                const Node& node = scene.nodes[std::size_t(inst.node)];
                if (node.mesh < 0) continue;
                for (const auto& prim : scene.meshes[std::size_t(node.mesh)].primitives)
                    for (const auto& p : prim.positions) {
                        glm::vec3 wp = glm::vec3(inst.world * glm::vec4(p, 1.0f));
                        found |= wp.z > 0.075f && std::fabs(wp.x - col[0]) < 0.02f && std::fabs(wp.y - y) < 0.02f;
                    }
            }
            EXPECT_TRUE(found) << "no hemisphere top at (" << col[0] << ", " << y << ")";
        }

    const int w = 512, h = 512;
    Frame f = render(*context, scene, View{0, 0}, settings_of_size(w, h));
    maybe_save(f.image, "NormalTangentTest_front");
    EXPECT_EQ(f.stats.gl_errors, "");

    for (int c = 0; c < 2; ++c)  // pink and blue; see above for gold
        for (float y : rows) {
            SphereStats s[2];
            for (int k = 0; k < 2; ++k) {
                glm::vec2 centre = project(f.camera, {columns[c][k], y, 0.0f}, w, h);
                float r = glm::length(project(f.camera, {columns[c][k] + radius, y, 0.0f}, w, h) - centre);
                s[k] = sphere_stats(f.image, centre, r);
            }
            double corr = pearson(s[0].patch, s[1].patch);
            std::printf("NormalTangentTest %-4s row y=%+.1f: real UR %.3f LL %.3f | normal-mapped UR %.3f LL %.3f | "
                        "correlation %.3f\n",
                        column_names[c], y, s[0].upper_right, s[0].lower_left, s[1].upper_right, s[1].lower_left,
                        corr);
            // Measured on llvmpipe: upper right 0.63..0.78, lower left 0.08..0.39.
            for (int k = 0; k < 2; ++k)
                EXPECT_GT(s[k].upper_right, s[k].lower_left + 0.15)
                    << column_names[c] << " column, row y=" << y << ", " << (k ? "normal-mapped" : "real")
                    << " hemisphere: the lit side is not towards the key light (upper right)";
            // The normal map reproduces the geometry's shading (measured: 0.96..1.0).
            EXPECT_GE(corr, 0.9) << column_names[c] << " column, row y=" << y
                                     << ": the normal-mapped hemisphere is shaded unlike the real one";
        }
}

// ---------------------------------------------------------------------------
// DamagedHelmetLights (KHR_lights_punctual: directional, point, spot) against
// the Khronos Sample Viewer's renders in ../shared/refs/khronos/punctual.

struct RefView {
    const char* ref;
    View view;
};

// What the Khronos references were rendered with, in our terms: 512^2, the neutral tone
// mapper, pow(1/2.2) encoding, black background (`--tonemap neutral --encoding gamma2.2
// --background 0,0,0`).
RenderSettings khronos_reference_settings() {
    RenderSettings s = settings_of_size(512, 512);
    s.tone_mapper = ToneMapper::Neutral;
    s.encoding = Encoding::Gamma22;
    s.background = glm::vec4(0, 0, 0, 1);
    s.shadows = Shadows::Off;  // the Khronos Sample Viewer has none
    return s;
}

// An environment file baked at the default settings, without the user's cache (hermetic).
ibl::BakedIbl bake_uncached(const fs::path& env_file) {
    ibl::EnvironmentSource source;
    source.kind = ibl::EnvironmentSource::Kind::File;
    source.path = env_file;
    return ibl::load_or_bake(source, ibl::BakeOptions{}, {}, /*use_cache=*/false);
}

// Metrics of a display-encoded render against a reference image, printed under `label`.
ImageMetrics compare_to_reference(const ImageF& image, const Image8& ref, const std::string& label) {
    ImageMetrics m = compare_images(to_image8(image, false), ref);
    std::printf("%s: PSNR %.2f dB, MAD %.2f, p99 %.0f over %zu pixels\n", label.c_str(), m.psnr_db, m.mad, m.p99,
                m.pixels);
    return m;
}

TEST(DamagedHelmetLights, MatchesKhronosReference) {
    REQUIRE_SHARED_MODELS();
    fs::path file = model_path("DamagedHelmetLights");
    fs::path refs = kSharedDir / "refs" / "khronos" / "punctual";
    if (file.empty() || !fs::is_directory(refs)) GTEST_SKIP() << "DamagedHelmetLights or its references missing";
    REQUIRE_CONTEXT();
    Scene scene = load_model(file);
    ASSERT_FALSE(scene_lights(scene, flatten(scene)).empty()) << "the model's punctual lights were not loaded";
    for (const RefView& rv : {RefView{"DamagedHelmetLights_front.png", {0, 0}}, RefView{"DamagedHelmetLights_q.png", {45, 20}}}) {
        SCOPED_TRACE(rv.ref);
        Image8 ref = read_image8(refs / rv.ref);
        ASSERT_EQ(ref.width, 512);
        ASSERT_EQ(ref.height, 512);
        Frame f = render(*context, scene, rv.view, khronos_reference_settings());
        maybe_save(f.image, std::string("DamagedHelmetLights_") + rv.ref);
        EXPECT_EQ(f.stats.gl_errors, "");
        ImageMetrics m = compare_to_reference(f.image, ref, std::string("DamagedHelmetLights ") + rv.ref);
        EXPECT_GT(m.pixels, 512u * 512u / 10u);
        EXPECT_GE(m.psnr_db, 32.0);
    }
}

// ---------------------------------------------------------------------------
// Image-based light against the Khronos Sample Viewer's renders of the shared models
// in ../shared/refs/khronos/{studio,potsdamer} (its default IBL, no punctual lights):
// the same command a user runs, `--env X.hdr --no-scene-lights --tonemap neutral
// --encoding gamma2.2 --background 0,0,0`. Measured on llvmpipe (2026-12-01):
// 31.5..58.2 dB; the bar is the 30 dB the project promises.

// The environments of the Khronos references: (folder under refs/khronos, file under assets/env).
constexpr std::pair<const char*, const char*> kReferenceEnvironments[] = {{"studio", "studio_small_03_1k.hdr"},
                                                                         {"potsdamer", "potsdamer_platz_1k.hdr"}};

TEST(KhronosReferences, ImageBasedLight) {
    REQUIRE_SHARED_MODELS();
    const fs::path refs = kSharedDir / "refs" / "khronos";
    REQUIRE_CONTEXT();
    int compared = 0;
    for (auto [ref_folder, env_file] : kReferenceEnvironments) {
        fs::path env_path = kSharedDir / "assets" / "env" / env_file;
        if (!fs::is_directory(refs / ref_folder) || !fs::exists(env_path)) continue;
        ibl::BakedIbl baked = bake_uncached(env_path);
        std::vector<fs::path> files;
        for (const auto& e : fs::directory_iterator(refs / ref_folder))
            if (e.path().extension() == ".png") files.push_back(e.path());
        std::sort(files.begin(), files.end());
        for (const fs::path& ref_file : files) {
            // MODEL_front.png (yaw 0, pitch 0) or MODEL_q.png (yaw 45, pitch 20).
            std::string stem = ref_file.stem().string();
            std::size_t cut = stem.rfind('_');
            ASSERT_NE(cut, std::string::npos) << ref_file;
            std::string model = stem.substr(0, cut), view_name = stem.substr(cut + 1);
            fs::path file = model_path(model);
            if (file.empty()) continue;
            SCOPED_TRACE(std::string(ref_folder) + "/" + stem);
            View view = view_name == "q" ? View{45, 20} : View{0, 0};
            Scene scene = load_model(file);
            RenderSettings s = khronos_reference_settings();
            s.environment = &baked;
            Frame f = render(*context, scene, view, s, /*punctual_lights=*/false);
            maybe_save(f.image, std::string("ibl_") + ref_folder + "_" + stem);
            EXPECT_EQ(f.stats.gl_errors, "");
            ImageMetrics m = compare_to_reference(f.image, read_image8(ref_file), std::string(ref_folder) + "/" + stem);
            ++compared;
            if (m.pixels == 0) continue;  // the model is edge-on (TwoSidedPlane from the front): both black
            EXPECT_GE(m.psnr_db, 30.0);
        }
    }
    if (compared == 0) GTEST_SKIP() << "no Khronos IBL references in " << refs;
}

// DamagedHelmet under the studio environment (baked without the cache), for the tests that
// render it at kViews: the two reference views and a grazing 80 degrees, where the anisotropic
// filter takes most probes. helmet_under_studio() is empty when the model or the environment is
// missing from the shared folder.
struct HelmetUnderStudio {
    static constexpr View kViews[] = {View{0, 0}, View{45, 20}, View{0, 80}};
    Scene scene;
    ibl::BakedIbl baked;
    // The Khronos reference settings, lit by the environment alone.
    RenderSettings settings() const {
        RenderSettings s = khronos_reference_settings();
        s.environment = &baked;
        return s;
    }
    Frame render_at(gpu::Context& context, View view, const RenderSettings& s) const {
        return render(context, scene, view, s, /*punctual_lights=*/false);
    }
};

std::optional<HelmetUnderStudio> helmet_under_studio() {
    const fs::path file = model_path("DamagedHelmet");
    const fs::path env_path = kSharedDir / "assets" / "env" / "studio_small_03_1k.hdr";
    if (file.empty() || !fs::exists(env_path)) return std::nullopt;
    return HelmetUnderStudio{load_model(file), bake_uncached(env_path)};
}

std::string view_trace(View view) { return "yaw " + std::to_string(view.yaw) + " pitch " + std::to_string(view.pitch); }

// The default anisotropic filter (kDefaultAnisotropy probes at most) renders what the Khronos
// Sample Viewer's 16 render, to well below what the agreement figures can see: DamagedHelmet
// under image-based light, the reference views and one at a grazing 80 degrees. Measured on
// llvmpipe (2026-12-03): 61.9-65.0 dB between the two (p99 <= 1), where the Khronos figures are
// 34-37 dB.
TEST(KhronosReferences, DefaultAnisotropyRendersAsSixteen) {
    REQUIRE_SHARED_MODELS();
    REQUIRE_CONTEXT();
    ASSERT_LT(RenderSettings{}.anisotropy, 16.0f) << "the default is the Khronos viewer's 16: nothing to check";
    const std::optional<HelmetUnderStudio> helmet = helmet_under_studio();
    if (!helmet) GTEST_SKIP() << "DamagedHelmet or the studio environment missing";
    for (View view : HelmetUnderStudio::kViews) {
        SCOPED_TRACE(view_trace(view));
        RenderSettings s = helmet->settings();
        Frame by_default = helmet->render_at(*context, view, s);
        s.anisotropy = 16.0f;
        Frame sixteen = helmet->render_at(*context, view, s);
        ImageMetrics m = compare_images(to_image8(by_default.image, false), to_image8(sixteen.image, false));
        std::printf("DamagedHelmet yaw %g pitch %g, %g probes against 16: PSNR %.2f dB, p99 %.0f\n", double(view.yaw),
                    double(view.pitch), double(RenderSettings{}.anisotropy), m.psnr_db, m.p99);
        EXPECT_GE(m.psnr_db, 55.0);
        EXPECT_LE(m.p99, 1.0);
    }
}

// DamagedHelmet's base colour, metallic-roughness (with the occlusion) and normal maps share UV
// set, transform, size and probe limit, so the renderer reads them through one anisotropic
// footprint (feature::DetailSharedFootprint): the image is the one a footprint per map gives, to
// the last bit, at the reference views and at a grazing 80 degrees (where most probes are
// taken). A normal map read through another transform keeps its own footprint.
TEST(KhronosReferences, SharedFootprintRendersTheSameImage) {
    REQUIRE_SHARED_MODELS();
    REQUIRE_CONTEXT();
    std::optional<HelmetUnderStudio> helmet = helmet_under_studio();
    if (!helmet) GTEST_SKIP() << "DamagedHelmet or the studio environment missing";
    for (View view : HelmetUnderStudio::kViews) {
        SCOPED_TRACE(view_trace(view));
        RenderSettings s = helmet->settings();
        Frame shared = helmet->render_at(*context, view, s);
        s.share_footprints = false;
        Frame own = helmet->render_at(*context, view, s);
        EXPECT_EQ(shared.stats.shared_footprint_draws, 1);
        EXPECT_EQ(own.stats.shared_footprint_draws, 0);
        ASSERT_EQ(shared.image.pixels.size(), own.image.pixels.size());
        float worst = 0.0f;
        for (std::size_t i = 0; i < shared.image.pixels.size(); ++i)
            worst = std::max(worst, std::abs(shared.image.pixels[i] - own.image.pixels[i]));
        EXPECT_EQ(worst, 0.0f);
    }
    ASSERT_FALSE(helmet->scene.materials.empty());
    TextureTransform scaled;
    scaled.scale = glm::vec2(2.0f);
    for (Material& m : helmet->scene.materials) m.normal.set_transform(scaled);
    EXPECT_EQ(helmet->render_at(*context, View{0, 0}, helmet->settings()).stats.shared_footprint_draws, 0);
}

// DamagedHelmet's metallic-roughness texture is read from the alphas of its base colour and
// normal textures and its occlusion from the emissive's (feature::MetallicRoughnessInAlpha,
// RenderSettings::pack_channels), one texture fewer to probe: ~15 % of its frame. Metallic and
// roughness are the same texels through the same probes; the occlusion is filtered as the
// emissive is, without anisotropy, which moves single views by a few tenths of a dB either
// way against the Khronos Sample Viewer and their mean by less than 0.05 dB. Measured on
// llvmpipe (2026-12-04), packed against as stored: studio front 34.26 / 34.38 dB, q 35.63 /
// 35.52; potsdamer front 34.88 / 35.07, q 35.86 / 35.90; punctual lights front 36.25 / 36.10,
// q 37.36 / 37.22 (mean +0.01 dB); the packed and stored images 47.5-54.0 dB apart.
TEST(KhronosReferences, PackedChannelsKeepAgreement) {
    REQUIRE_SHARED_MODELS();
    const fs::path refs = kSharedDir / "refs" / "khronos";
    const fs::path helmet = model_path("DamagedHelmet"), lights = model_path("DamagedHelmetLights");
    if (helmet.empty() || lights.empty()) GTEST_SKIP() << "DamagedHelmet or DamagedHelmetLights missing";
    REQUIRE_CONTEXT();
    struct Case {
        const fs::path* model;
        const char* env_file;  // under assets/env; nullptr: the model's punctual lights
        fs::path ref;
        View view;
    };
    std::vector<Case> cases;
    for (auto [env, env_file] : kReferenceEnvironments)
        for (auto [name, view] : {std::pair{"front", View{0, 0}}, std::pair{"q", View{45, 20}}})
            cases.push_back({&helmet, env_file, refs / env / (std::string("DamagedHelmet_") + name + ".png"), view});
    for (auto [name, view] : {std::pair{"front", View{0, 0}}, std::pair{"q", View{45, 20}}})
        cases.push_back({&lights, nullptr, refs / "punctual" / (std::string("DamagedHelmetLights_") + name + ".png"), view});
    std::map<std::string, ibl::BakedIbl> bakes;
    double sum_change = 0.0;
    int compared = 0;
    for (const Case& c : cases) {
        if (!fs::exists(c.ref)) continue;
        SCOPED_TRACE(c.ref.string());
        Scene scene = load_model(*c.model);
        RenderSettings s = khronos_reference_settings();
        if (c.env_file) {
            const fs::path env_path = kSharedDir / "assets" / "env" / c.env_file;
            if (!fs::exists(env_path)) continue;
            if (!bakes.count(c.env_file)) bakes.emplace(c.env_file, bake_uncached(env_path));
            s.environment = &bakes.at(c.env_file);
        }
        const Image8 ref = read_image8(c.ref);
        Frame packed = render(*context, scene, c.view, s, /*punctual_lights=*/c.env_file == nullptr);
        s.pack_channels = false;
        Frame stored = render(*context, scene, c.view, s, /*punctual_lights=*/c.env_file == nullptr);
        EXPECT_EQ(packed.stats.alpha_packed_draws, 1);
        EXPECT_EQ(stored.stats.alpha_packed_draws, 0);
        const ImageMetrics mp = compare_images(to_image8(packed.image, false), ref);
        const ImageMetrics ms = compare_images(to_image8(stored.image, false), ref);
        const ImageMetrics between = compare_images(to_image8(packed.image, false), to_image8(stored.image, false));
        std::printf("%s: packed %.2f dB, as stored %.2f dB against Khronos (%+.2f); the two %.2f dB apart\n",
                    (c.ref.parent_path().filename() / c.ref.filename()).string().c_str(), mp.psnr_db, ms.psnr_db, mp.psnr_db - ms.psnr_db,
                    between.psnr_db);
        EXPECT_GE(mp.psnr_db, ms.psnr_db - 0.3);
        EXPECT_GE(between.psnr_db, 45.0);
        sum_change += mp.psnr_db - ms.psnr_db;
        ++compared;
    }
    if (compared == 0) GTEST_SKIP() << "no DamagedHelmet references in " << refs;
    std::printf("mean change over %d views: %+.3f dB\n", compared, sum_change / compared);
    EXPECT_GE(sum_change / compared, -0.05);
}

// ---------------------------------------------------------------------------
// KHR_materials_transmission, _volume and _dispersion against the Khronos Sample Renderer: the
// scenes of scripts/make-transmission-scenes.py (tests/data/transmission: two glass spheres in
// front of a textured backdrop) and its images of them in tests/data/transmission/refs
// (studio environment, no punctual lights, 320^2, the views front = yaw 0 pitch 0 and
// q = yaw 30 pitch 20; README.md there says how they were made). Each floor is the PSNR
// measured on llvmpipe (2026-12-02) less a margin of about 1.5 dB.

struct TransmissionCase {
    const char* scene;
    const char* view_name;
    View view;
    double floor_db;
};

TEST(KhronosReferences, Transmission) {
    const fs::path dir = fs::path(FRESNEL_SOURCE_DIR) / "tests" / "data" / "transmission";
    const fs::path env_path = kSharedDir / "assets" / "env" / "studio_small_03_1k.hdr";
    if (!fs::exists(env_path)) GTEST_SKIP() << env_path << " not found (the shared folder)";
    REQUIRE_CONTEXT();
    ibl::BakedIbl baked = bake_uncached(env_path);
    RenderSettings s = khronos_reference_settings();
    s.width = s.height = 320;
    s.environment = &baked;
    const TransmissionCase cases[] = {
        // Measured: 35.14, 34.91, 35.11, 36.06, 34.83, 35.52 dB.
        {"transmission", "front", {0, 0}, 33.6}, {"transmission", "q", {30, 20}, 33.4},
        {"volume", "front", {0, 0}, 33.6},       {"volume", "q", {30, 20}, 34.5},
        {"dispersion", "front", {0, 0}, 33.3},   {"dispersion", "q", {30, 20}, 34.0},
    };
    for (const TransmissionCase& c : cases) {
        const std::string name = std::string(c.scene) + "_" + c.view_name;
        SCOPED_TRACE(name);
        Scene scene = load_model(dir / (std::string(c.scene) + ".gltf"));
        Image8 ref = read_image8(dir / "refs" / (name + ".png"));
        Frame f = render(*context, scene, c.view, s, /*punctual_lights=*/false);
        maybe_save(f.image, "transmission_" + name);
        EXPECT_EQ(f.stats.gl_errors, "");
        ImageMetrics m = compare_to_reference(f.image, ref, "transmission/" + name);
        EXPECT_GT(m.pixels, 320u * 320u / 4u);
        EXPECT_GE(m.psnr_db, c.floor_db);
        if (std::string(c.scene) == "volume" && c.view.yaw == 0) {
            // The comparison catches a fake: the same spheres without transmission (opaque
            // white plastic) fall far below the floor.
            for (auto& mat : scene.materials) mat.transmission.reset();
            Frame opaque = render(*context, scene, c.view, s, false);
            ImageMetrics mo = compare_to_reference(opaque.image, ref, "transmission/" + name + " without transmission");
            EXPECT_LT(mo.psnr_db, c.floor_db - 5.0);
        }
    }
}

}  // namespace
