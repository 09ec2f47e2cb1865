// RenderTarget::DefaultFramebuffer: the frame written into a context's default framebuffer
// (here an EGL pbuffer standing in for a window) is the image render() reads back offscreen.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "fresnel/core/error.h"
#include "fresnel/core/metrics.h"
#include "fresnel/gpu/context.h"
#include "fresnel/gpu/device.h"
#include "fresnel/core/color.h"
#include <glm/gtc/matrix_transform.hpp>

#include "fresnel/job/camera.h"
#include "fresnel/job/lights.h"
#include "fresnel/render/renderer.h"
#include "fresnel/scene/mesh_ops.h"
#include "fresnel/scene/procedural.h"
#include "headless_context.h"

using namespace fresnel;

namespace {
// The demo scene, set on a renderer of `context`.
struct DemoScene {
    Scene scene = make_demo_scene();
    Renderer renderer;
    explicit DemoScene(gpu::Context& context) : renderer(context) { renderer.set_scene(scene); }
    // The orbit camera on the whole scene for a w x h frame.
    CameraSetup camera(int w, int h) const { return orbit_camera(scene_bounds(scene, flatten(scene)), {}, w, h); }
};

// The suite's tests: a headless context (with a w x h pbuffer as its default framebuffer when
// asked) and the demo scene on a renderer; a test without a context skips, saying why.
class RenderTargets : public ::testing::Test {
protected:
    bool start(int surface_width = 0, int surface_height = 0) {
        gpu::ContextOptions co;
        co.surface_width = surface_width;
        co.surface_height = surface_height;
        context_ = test_support::try_headless_context(why_, co);
        if (!context_) {
            why_ = std::string(surface_width > 0 ? "no EGL pbuffer: " : "no headless OpenGL context: ") + why_;
            return false;
        }
        demo_ = std::make_unique<DemoScene>(*context_);
        return true;
    }
    std::string why_;
    std::unique_ptr<gpu::Context> context_;
    std::unique_ptr<DemoScene> demo_;
};

// The default framebuffer's pixels (GL rows bottom to top) of the viewport at (x, y) as an image.
Image8 read_window(int x, int y, int w, int h) {
    gpu::Device device;
    std::vector<std::uint8_t> px = device.read_default_rgba8(x, y, w, h);
    Image8 img(w, h, 3);
    for (int row = 0; row < h; ++row)
        for (int col = 0; col < w; ++col)
            for (int c = 0; c < 3; ++c)
                img.at(col, row)[c] = px[(std::size_t(h - 1 - row) * std::size_t(w) + std::size_t(col)) * 4 + std::size_t(c)];
    return img;
}
}  // namespace

TEST_F(RenderTargets, DefaultFramebufferShowsTheOffscreenFrame) {
    if (!start(200, 150)) GTEST_SKIP() << why_;
    Renderer& renderer = demo_->renderer;
    RenderSettings rs;
    rs.width = 160;
    rs.height = 120;
    rs.background = glm::vec4(0.1f, 0.2f, 0.3f, 1.0f);
    CameraSetup cam = demo_->camera(rs.width, rs.height);
    auto lights = default_lights();

    Image8 offscreen = to_image8(renderer.render(cam, lights, rs), false);
    // Into the window, at an offset: the rest of the window keeps its clear colour.
    gpu::Device device;
    device.bind_framebuffer(nullptr);
    device.viewport(0, 0, 200, 150);
    device.clear(glm::vec4(1.0f, 0.0f, 1.0f, 1.0f), true);
    FrameStats stats;
    renderer.draw(cam, lights, rs, RenderTarget::default_framebuffer(20, 10), &stats);
    renderer.finish();
    EXPECT_EQ(stats.gl_errors, "");
    EXPECT_GT(stats.draw_calls, 0);

    Image8 window = read_window(20, 10, rs.width, rs.height);
    ImageMetrics m = compare_images(window, offscreen, false);
    std::printf("default framebuffer vs offscreen: PSNR %.2f dB, max %.0f over %zu pixels\n", m.psnr_db, m.max_abs, m.pixels);
    EXPECT_EQ(m.pixels, std::size_t(rs.width) * rs.height);
    EXPECT_GE(m.psnr_db, 50.0);  // the same frame; 8-bit targets may round differently by one step
    // Outside the viewport the clear colour is untouched.
    Image8 corner = read_window(0, 0, 10, 10);
    EXPECT_EQ(corner.at(5, 5)[0], 255);
    EXPECT_EQ(corner.at(5, 5)[1], 0);
    // The frame is not empty: the centre shows spheres, brighter than the background.
    const std::uint8_t* c = window.at(rs.width / 2, rs.height / 2);
    EXPECT_GT(int(c[0]) + c[1] + c[2], 3 * 40);
}

// A scissor rectangle: a second frame with other settings replaces only its pixels (the
// viewer's split view); the rest keeps the first frame.
TEST_F(RenderTargets, ScissorWritesOnlyItsRectangle) {
    if (!start(160, 120)) GTEST_SKIP() << why_;
    Renderer& renderer = demo_->renderer;
    RenderSettings a;
    a.width = 160;
    a.height = 120;
    RenderSettings b = a;
    b.debug = DebugChannel::Roughness;
    CameraSetup cam = demo_->camera(a.width, a.height);
    auto lights = default_lights();
    Image8 shaded = to_image8(renderer.render(cam, lights, a), false);
    Image8 rough = to_image8(renderer.render(cam, lights, b), false);

    renderer.draw(cam, lights, a, RenderTarget::default_framebuffer());
    RenderTarget right = RenderTarget::default_framebuffer();
    right.scissor = RenderTarget::Rect{100, 0, 60, 120};
    FrameStats stats;
    renderer.draw(cam, lights, b, right, &stats);
    renderer.finish();
    EXPECT_EQ(stats.gl_errors, "");
    Image8 window = read_window(0, 0, 160, 120);
    auto crop = [](const Image8& im, int x0, int x1) {
        Image8 out(x1 - x0, im.height, 3);
        for (int y = 0; y < im.height; ++y)
            for (int x = x0; x < x1; ++x)
                for (int c = 0; c < 3; ++c) out.at(x - x0, y)[c] = im.at(x, y)[c];
        return out;
    };
    double left_psnr = compare_images(crop(window, 0, 100), crop(shaded, 0, 100), false).psnr_db;
    double right_psnr = compare_images(crop(window, 100, 160), crop(rough, 100, 160), false).psnr_db;
    std::printf("split: left vs shaded %.1f dB, right vs roughness %.1f dB\n", left_psnr, right_psnr);
    EXPECT_GE(left_psnr, 50.0);
    EXPECT_GE(right_psnr, 50.0);
    // And the two settings differ, so the test can tell the halves apart.
    EXPECT_LT(compare_images(shaded, rough, false).psnr_db, 30.0);
}

// The display transform compiled into each frame's shaders (FrameVariant: FRAME_TONEMAP,
// FRAME_ENCODING) against the C++ tone mappers and encodings applied to the same frame drawn
// linear (no tone map, no encoding), for every tone mapper and encoding, with and without
// punctual lights (FRAME_NO_LIGHTS). One sample per pixel, so no edge mixes display values.
TEST_F(RenderTargets, CompiledDisplayTransformMatchesTheCppOne) {
    if (!start()) GTEST_SKIP() << why_;
    Renderer& renderer = demo_->renderer;
    RenderSettings rs;
    rs.width = 48;
    rs.height = 36;
    rs.msaa = 1;
    rs.exposure_ev = 0.5f;
    rs.ambient = glm::vec3(0.3f);  // lights the frame without punctual lights
    const CameraSetup cam = demo_->camera(rs.width, rs.height);
    int compared = 0;
    for (bool with_lights : {true, false}) {
        const std::vector<LightInstance> lights = with_lights ? default_lights() : std::vector<LightInstance>{};
        RenderSettings linear = rs;
        linear.tone_mapper = ToneMapper::None;
        linear.encoding = std::nullopt;
        linear.exposure_ev = 0.0f;
        const ImageF radiance = renderer.render(cam, lights, linear);
        for (int t = 0; t <= int(ToneMapper::None); ++t)
            for (std::optional<Encoding> e : {std::optional<Encoding>{}, std::optional<Encoding>(Encoding::Srgb),
                                              std::optional<Encoding>(Encoding::Gamma22)}) {
                RenderSettings display = rs;
                display.tone_mapper = ToneMapper(t);
                display.encoding = e;
                const ImageF got = renderer.render(cam, lights, display);
                float worst = 0.0f;
                for (int y = 0; y < rs.height; ++y)
                    for (int x = 0; x < rs.width; ++x) {
                        const float* r = radiance.at(x, y);
                        glm::vec3 c = tone_map(ToneMapper(t), glm::vec3(r[0], r[1], r[2]) * exposure_scale(rs.exposure_ev));
                        if (e) c = encode_display(*e, c);
                        const float* g = got.at(x, y);
                        for (int k = 0; k < 3; ++k)
                            worst = std::max(worst, std::abs(g[k] - c[k]) / std::max(1.0f, std::abs(c[k])));
                    }
                EXPECT_LT(worst, 2e-3f) << "tone mapper " << t << ", encoding " << (e ? int(*e) : -1)
                                        << (with_lights ? ", lights" : ", no lights");
                ++compared;
            }
    }
    EXPECT_EQ(compared, 2 * 6 * 3);
}

// RenderSettings::FrameFormat::Display8: the multisampled frame is 8-bit (every resolved value
// is a mean of 4 samples of k/255, so on the grid of 1/1020), each pixel within about 1/255
// of the Float frame's (the samples are quantised before the resolve averages them); frames
// without a display encoding, transparent frames and debug channels stay Float.
TEST_F(RenderTargets, Display8FrameIsTheFloatFrameQuantised) {
    if (!start()) GTEST_SKIP() << why_;
    Renderer& renderer = demo_->renderer;
    RenderSettings rs;
    rs.width = 96;
    rs.height = 72;
    rs.msaa = 4;
    rs.background = glm::vec4(0.1f, 0.2f, 0.3f, 1.0f);
    const CameraSetup cam = demo_->camera(rs.width, rs.height);
    const std::vector<LightInstance> lights = default_lights();
    // How many channel values lie off the 1/1020 grid, and the largest difference from `ref`.
    auto grid_and_difference = [&](const ImageF& img, const ImageF& ref) {
        std::pair<int, float> r{0, 0.0f};
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                for (int k = 0; k < 3; ++k) {
                    float v = img.at(x, y)[k] * 1020.0f;
                    if (std::abs(v - std::round(v)) > 0.02f) ++r.first;
                    r.second = std::max(r.second, std::abs(img.at(x, y)[k] - ref.at(x, y)[k]));
                }
        return r;
    };
    RenderSettings as_float = rs;
    as_float.frame_format = RenderSettings::FrameFormat::Float;
    RenderSettings as_8bit = rs;
    as_8bit.frame_format = RenderSettings::FrameFormat::Display8;
    const ImageF f = renderer.render(cam, lights, as_float);
    const ImageF d = renderer.render(cam, lights, as_8bit);
    auto [off_grid_float, none] = grid_and_difference(f, f);
    auto [off_grid_8bit, diff] = grid_and_difference(d, f);
    std::printf("Display8 vs Float: %d / %d float values off the 1/1020 grid, 8-bit %d; largest difference %.5f\n",
                off_grid_float, rs.width * rs.height * 3, off_grid_8bit, double(diff));
    EXPECT_GT(off_grid_float, rs.width * rs.height);  // the float frame is not quantised
    EXPECT_EQ(off_grid_8bit, 0);                        // the 8-bit one is
    EXPECT_LE(diff, 1.0f / 255.0f + 1e-4f);
    EXPECT_GT(diff, 0.0f);
    // Without an encoding (linear output) the frame stays float: Display8 changes nothing.
    for (RenderSettings* s : {&as_float, &as_8bit}) s->encoding = std::nullopt;
    const ImageF lf = renderer.render(cam, lights, as_float);
    const ImageF ld = renderer.render(cam, lights, as_8bit);
    EXPECT_EQ(grid_and_difference(ld, lf).second, 0.0f);
    // A transparent frame stays float (un-premultiplying 8-bit samples would lose precision).
    for (RenderSettings* s : {&as_float, &as_8bit}) {
        s->encoding = Encoding::Srgb;
        s->background = glm::vec4(0.0f);
    }
    const ImageF tf = renderer.render(cam, lights, as_float);
    const ImageF td = renderer.render(cam, lights, as_8bit);
    EXPECT_EQ(grid_and_difference(td, tf).second, 0.0f);
}

// The 8-bit offscreen target (render8): the frame render() gives, quantised by the GPU as
// to_image8 quantises it, opaque and transparent, 8-bit and float frame formats.
TEST_F(RenderTargets, Offscreen8IsTheFloatImageQuantised) {
    if (!start()) GTEST_SKIP() << why_;
    Renderer& renderer = demo_->renderer;
    const std::vector<LightInstance> lights = default_lights();
    for (bool transparent : {false, true}) {
        for (auto format : {RenderSettings::FrameFormat::Display8, RenderSettings::FrameFormat::Float}) {
            RenderSettings rs;
            rs.width = 80;
            rs.height = 60;
            rs.frame_format = format;
            rs.background = transparent ? glm::vec4(0.0f) : glm::vec4(0.1f, 0.2f, 0.3f, 1.0f);
            const CameraSetup cam = demo_->camera(rs.width, rs.height);
            FrameStats stats;
            const Image8 want = to_image8(renderer.render(cam, lights, rs), transparent);
            const Image8 got = renderer.render8(cam, lights, rs, transparent, &stats);
            EXPECT_EQ(stats.gl_errors, "");
            ASSERT_EQ(got.width, want.width);
            ASSERT_EQ(got.height, want.height);
            ASSERT_EQ(got.channels, transparent ? 4 : 3);
            int off = 0, largest = 0, covered = 0;
            for (std::size_t i = 0; i < got.pixels.size(); ++i) {
                const int d = std::abs(int(got.pixels[i]) - int(want.pixels[i]));
                off += d != 0;
                largest = std::max(largest, d);
            }
            for (int y = 0; y < got.height; ++y)
                for (int x = 0; x < got.width; ++x) covered += transparent && got.at(x, y)[3] > 0;
            std::printf("render8 vs to_image8(render()), %s, %s frame: %d of %zu values differ, by at most %d\n",
                        transparent ? "transparent" : "opaque",
                        format == RenderSettings::FrameFormat::Display8 ? "8-bit" : "float", off, got.pixels.size(),
                        largest);
            EXPECT_LE(largest, 1);
            // Ties only: the 8-bit frame's resolve averages four 8-bit samples, which lands on a
            // half step for about one value in a hundred, and GL leaves the rounding of a tie open.
            EXPECT_LE(off, int(got.pixels.size() / 25));
            if (transparent) {
                EXPECT_GT(covered, got.width * got.height / 10);  // the spheres, not an empty frame
            }
        }
    }
}

// Frames that alternate between the two formats (the viewer's split view: the 8-bit frame on
// the left, a debug channel, which is half float, on the right) keep a set of targets each.
TEST_F(RenderTargets, AlternatingFrameFormatsKeepTheirTargets) {
    if (!start()) GTEST_SKIP() << why_;
    Renderer& renderer = demo_->renderer;
    RenderSettings left;
    left.width = 64;
    left.height = 48;
    left.frame_format = RenderSettings::FrameFormat::Display8;
    RenderSettings right = left;
    right.debug = DebugChannel::Normal;  // a debug channel: a half-float frame
    const CameraSetup cam = demo_->camera(left.width, left.height);
    const std::vector<LightInstance> lights = default_lights();
    for (int frame = 0; frame < 4; ++frame)
        for (const RenderSettings* s : {&left, &right}) {
            FrameStats stats;
            renderer.draw(cam, lights, *s, &stats);
            EXPECT_EQ(stats.gl_errors, "");
            EXPECT_EQ(stats.targets_rebuilt, frame == 0) << "frame " << frame << (s == &left ? ", 8-bit" : ", debug");
        }
    // A new size rebuilds them.
    left.width = 80;
    FrameStats stats;
    renderer.draw(cam, lights, left, &stats);
    EXPECT_TRUE(stats.targets_rebuilt);
    renderer.finish();
}

// Shadow maps are drawn when what they show changes and kept otherwise: a still frame drawn
// again reuses them (the same picture), a moved light or node redraws them, --shadows off draws
// none, and a frame with shadows after one without finds them still valid.
TEST_F(RenderTargets, ShadowMapsAreKeptWhileNothingMoves) {
    if (!start()) GTEST_SKIP() << why_;
    Renderer& renderer = demo_->renderer;
    RenderSettings s;
    s.width = s.height = 64;
    s.shadow_map_size = 256;
    const CameraSetup cam = demo_->camera(s.width, s.height);
    std::vector<LightInstance> lights = default_lights();  // two directional lights, two cascades each
    auto frame = [&](const std::vector<LightInstance>& l, const RenderSettings& settings) {
        FrameStats stats;
        ImageF image = renderer.render(cam, l, settings, &stats);
        EXPECT_EQ(stats.gl_errors, "");
        return std::pair{stats.shadow_tiles_drawn, image};
    };
    auto [first_tiles, first] = frame(lights, s);
    EXPECT_EQ(first_tiles, 4);
    auto [again_tiles, again] = frame(lights, s);
    EXPECT_EQ(again_tiles, 0) << "a still frame redrew its shadow maps";
    EXPECT_EQ(first.pixels, again.pixels);
    lights[0].direction = direction_from_angles(60.0f, 40.0f);
    EXPECT_EQ(frame(lights, s).first, 4) << "a moved light";
    RenderSettings off = s;
    off.shadows = Shadows::Off;
    EXPECT_EQ(frame(lights, off).first, 0);
    EXPECT_EQ(frame(lights, s).first, 0) << "nothing moved while shadows were off";
    for (Node& n : demo_->scene.nodes) n.local = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.1f, 0.0f)) * n.local;
    renderer.update_transforms();
    EXPECT_EQ(frame(lights, s).first, 4) << "a moved node";
    renderer.finish();
}

// A 64^2 RGBA image of byte noise (a linear congruential sequence from `seed`), the texels of
// the packing tests: every channel different, so a channel read from the wrong place shows.
namespace {
Image8 noise_image(std::uint32_t seed) {
    Image8 img(64, 64, 4);
    for (auto& v : img.pixels) {
        seed = seed * 1664525u + 1013904223u;
        v = std::uint8_t(seed >> 24);
    }
    return img;
}

// A material reading five maps (textures 0-4): base colour, metallic-roughness, normal,
// emissive and, with `occlusion`, occlusion.
Material five_map_material(bool occlusion) {
    Material m;
    m.base_color_factor = glm::vec4(0.9f, 0.8f, 0.7f, 1.0f);
    m.emissive_factor = glm::vec3(0.5f);
    m.base_color.texture = 0;
    m.metallic_roughness.texture = 1;
    m.normal.texture = 2;
    m.emissive.texture = 3;
    if (occlusion) {
        m.occlusion.texture = 4;
        m.occlusion_strength = 0.8f;
    }
    return m;
}

// A normal map of noise: z up, x and y random.
Image8 noise_normals(std::uint32_t seed) {
    Image8 normals = noise_image(seed);
    for (std::size_t i = 2; i < normals.pixels.size(); i += 4) normals.pixels[i] = 255;
    return normals;
}
}  // namespace

// The occlusion read from the metallic-roughness texture's R channel (the renderer's packing of
// two images, or one ORM texture: feature::OcclusionInMetallicRoughness) is the occlusion read
// from its own texture through the same anisotropic probes: a sphere whose occlusion is on
// TEXCOORD_1 (a copy of TEXCOORD_0, so it cannot be packed) renders the same frame.
TEST_F(RenderTargets, PackedOcclusionIsTheOcclusionMap) {
    if (!start()) GTEST_SKIP() << why_;
    const Image8 mr = noise_image(1), ao = noise_image(2);
    Image8 orm = mr;
    for (std::size_t i = 0; i < orm.pixels.size(); i += 4) orm.pixels[i] = ao.pixels[i];
    enum Layout { Packed, Separate, Orm };
    auto scene_with = [&](Layout layout) {
        Material m;
        m.base_color_factor = glm::vec4(0.8f, 0.7f, 0.6f, 1.0f);
        m.metallic_roughness.texture = layout == Orm ? 2 : 0;
        m.occlusion.texture = layout == Orm ? 2 : 1;
        m.occlusion.tex_coord = layout == Separate ? 1 : 0;
        m.occlusion_strength = 0.9f;
        Primitive p = make_uv_sphere(48, 24);
        for (auto& uv : p.uv0) uv *= 6.0f;  // minified and, near the rim, anisotropic
        p.uv1 = p.uv0;
        p.material = 0;
        Scene s = make_single_primitive_scene(std::move(p), {m});
        s.images = {{"metallic-roughness", mr}, {"occlusion", ao}, {"orm", orm}};
        s.textures = {{0, {}}, {1, {}}, {2, {}}};
        return s;
    };
    RenderSettings rs;
    rs.width = rs.height = 96;
    rs.ambient = glm::vec3(1.0f);  // the occlusion darkens indirect light only
    for (DebugChannel channel : {DebugChannel::None, DebugChannel::Occlusion}) {
        rs.debug = channel;
        std::vector<ImageF> frames;
        std::vector<std::size_t> bytes;
        for (Layout layout : {Packed, Separate, Orm}) {
            Scene scene = scene_with(layout);
            Renderer renderer(*context_);
            renderer.set_scene(scene);
            CameraSetup cam = orbit_camera(scene_bounds(scene, flatten(scene)), {}, rs.width, rs.height);
            FrameStats stats;
            frames.push_back(renderer.render(cam, default_lights(), rs, &stats));
            EXPECT_EQ(stats.gl_errors, "");
            bytes.push_back(renderer.texture_bytes());
        }
        // Packed, the two images are one texture, as the ORM image is; apart, one more 64^2 RGBA8
        // texture with its mip chain (5461 texels).
        EXPECT_EQ(bytes[0], bytes[2]);
        EXPECT_EQ(bytes[1], bytes[0] + 5461u * 4u);
        float max_diff = 0.0f, spread = 0.0f;
        for (std::size_t i = 0; i < frames[0].pixels.size(); ++i) {
            max_diff = std::max({max_diff, std::abs(frames[0].pixels[i] - frames[1].pixels[i]),
                                 std::abs(frames[2].pixels[i] - frames[1].pixels[i])});
            spread = std::max(spread, std::abs(frames[1].pixels[i] - frames[1].pixels[0]));
        }
        std::printf("%s: packed / ORM against the separate occlusion map: max difference %g (frame range %g)\n",
                    channel == DebugChannel::None ? "shaded" : "occlusion channel", double(max_diff), double(spread));
        EXPECT_LE(max_diff, 1e-6f);
        EXPECT_GT(spread, 0.1f);  // the frames show the sphere, not only the background
    }
}

// The metallic-roughness texture read from the alphas of the base colour and normal textures
// (and its occlusion from the emissive's: feature::MetallicRoughnessInAlpha) is the texture
// read as stored: frames with RenderSettings::pack_channels on and off are the same, with one
// texture fewer. A sphere with noise in every map, minified and anisotropic near the rim; the
// occlusion, which in the emissive's alpha is filtered without anisotropy, is one value, so
// no filter can tell the two apart. Materials that cannot pack (blended, or a map on another UV
// set) draw as stored. With nearest sampling the frames are equal to the bit; filtered, they
// differ by the sampler's precision (llvmpipe filters 8-bit unorm texels in fixed point and
// sRGB ones, whose alpha now holds the metallic, in float: measured 0.002 at most).
TEST_F(RenderTargets, MetallicRoughnessInAlphaIsTheSameImage) {
    if (!start()) GTEST_SKIP() << why_;
    Image8 flat_occlusion(64, 64, 4);
    for (std::size_t i = 0; i < flat_occlusion.pixels.size(); ++i) flat_occlusion.pixels[i] = i % 4 == 0 ? 90 : 255;
    const Image8 normals = noise_normals(3);
    enum Case { Plain, WithOcclusion, Blended, OtherUvSet };
    auto scene_with = [&](Case c) {
        Material m = five_map_material(c == WithOcclusion);
        if (c == Blended) m.alpha_mode = AlphaMode::Blend;
        if (c == OtherUvSet) m.normal.tex_coord = 1;
        Primitive p = make_uv_sphere(48, 24);
        for (auto& uv : p.uv0) uv *= 6.0f;
        p.uv1 = p.uv0;
        EXPECT_TRUE(generate_tangents(p, 0));
        p.material = 0;
        Scene s = make_single_primitive_scene(std::move(p), {m});
        s.images = {{"base colour", noise_image(1)}, {"metallic-roughness", noise_image(2)}, {"normal", normals},
                    {"emissive", noise_image(4)}, {"occlusion", flat_occlusion}};
        s.textures = {{0, {}}, {1, {}}, {2, {}}, {3, {}}, {4, {}}};
        return s;
    };
    RenderSettings rs;
    rs.width = rs.height = 96;
    rs.ambient = glm::vec3(1.0f);
    std::map<Case, std::size_t> packed_bytes;
    for (Case c : {Plain, WithOcclusion, Blended, OtherUvSet}) {
        for (bool filtered : {false, true}) {
            SCOPED_TRACE(std::to_string(int(c)) + (filtered ? " trilinear" : " nearest"));
            Scene scene = scene_with(c);
            if (!filtered)
                for (auto& t : scene.textures) t.sampler = Sampler{Filter::Nearest, Filter::Nearest, MipmapMode::Nearest};
            std::vector<ImageF> frames;
            std::vector<std::size_t> bytes;
            std::vector<int> packed_draws;
            for (bool pack : {true, false}) {
                rs.pack_channels = pack;
                Renderer renderer(*context_);
                renderer.set_scene(scene);
                CameraSetup cam = orbit_camera(scene_bounds(scene, flatten(scene)), {}, rs.width, rs.height);
                FrameStats stats;
                frames.push_back(renderer.render(cam, default_lights(), rs, &stats));
                EXPECT_EQ(stats.gl_errors, "");
                bytes.push_back(renderer.texture_bytes());
                packed_draws.push_back(stats.alpha_packed_draws);
            }
            const bool packs = c == Plain || c == WithOcclusion;
            EXPECT_EQ(packed_draws[0], packs ? 1 : 0);
            EXPECT_EQ(packed_draws[1], 0);
            if (filtered) packed_bytes[c] = bytes[0];
            float max_diff = 0.0f, spread = 0.0f;
            for (std::size_t i = 0; i < frames[0].pixels.size(); ++i) {
                max_diff = std::max(max_diff, std::abs(frames[0].pixels[i] - frames[1].pixels[i]));
                spread = std::max(spread, std::abs(frames[1].pixels[i] - frames[1].pixels[0]));
            }
            std::printf("case %d, %s: packed against as stored: max difference %g (frame range %g)\n", int(c),
                        filtered ? "trilinear" : "nearest", double(max_diff), double(spread));
            EXPECT_LE(max_diff, filtered ? 4e-3f : 0.0f);
            EXPECT_GT(spread, 0.1f);
        }
    }
    // Packed, the metallic-roughness texture (64^2 RGBA8 and its mip chain: 5461 texels) is not
    // uploaded, and the occlusion costs no texture either (as stored, it would be packed with
    // the metallic-roughness texture); a material that cannot pack uploads its four.
    EXPECT_EQ(packed_bytes[WithOcclusion], packed_bytes[Plain]);
    EXPECT_EQ(packed_bytes[OtherUvSet], packed_bytes[Plain] + 5461u * 4u);
}

// Renderer::ImageResidency::GpuOnly (a one-shot `fresnel render`): each image whose encoded
// bytes the scene keeps is freed once its textures are uploaded (an image one packed key alone
// reads is packed in place), and the frames are the ones of a renderer that kept them, to the
// bit: the frame set_scene uploaded for, and frames with other settings that make textures
// afterwards (channels not packed, a debug view's maps as stored), which decode the released
// images again. An image without encoded bytes stays.
TEST_F(RenderTargets, ReleasedImagesDrawTheSameFrames) {
    if (!start()) GTEST_SKIP() << why_;
    Primitive p = make_uv_sphere(48, 24);
    for (auto& uv : p.uv0) uv *= 3.0f;
    ASSERT_TRUE(generate_tangents(p, 0));
    p.material = 0;
    Scene kept = make_single_primitive_scene(std::move(p), {five_map_material(true)});
    kept.images = {{"base colour", noise_image(1)}, {"metallic-roughness", noise_image(2)}, {"normal", noise_normals(3)},
                   {"emissive", noise_image(4)}, {"occlusion", noise_image(5)}};
    kept.textures = {{0, {}}, {1, {}}, {2, {}}, {3, {}}, {4, {}}};
    Scene released = kept;
    for (std::size_t i = 0; i + 1 < released.images.size(); ++i)  // the occlusion without its bytes
        released.images[i].encoded =
            std::make_shared<const std::vector<std::uint8_t>>(encode_png(released.images[i].pixels));

    RenderSettings rs;
    rs.width = rs.height = 96;
    rs.ambient = glm::vec3(1.0f);
    Renderer keeping(*context_), releasing(*context_);
    keeping.set_scene(kept);
    releasing.set_scene(released, -1, Renderer::ImageResidency::GpuOnly);
    for (std::size_t i = 0; i < released.images.size(); ++i) {
        SCOPED_TRACE(released.images[i].name);
        EXPECT_EQ(released.images[i].released(), i + 1 < released.images.size());
        EXPECT_EQ(released.images[i].pixels.width, kept.images[i].pixels.width);  // the size stays
        EXPECT_FALSE(kept.images[i].released());
    }
    const CameraSetup cam = orbit_camera(scene_bounds(kept, flatten(kept)), {}, rs.width, rs.height);
    auto compare = [&](const char* what) {
        SCOPED_TRACE(what);
        FrameStats a, b;
        const ImageF want = keeping.render(cam, default_lights(), rs, &a);
        const ImageF got = releasing.render(cam, default_lights(), rs, &b);
        EXPECT_EQ(b.gl_errors, "");
        ASSERT_EQ(got.pixels.size(), want.pixels.size());
        float max_diff = 0.0f, spread = 0.0f;
        for (std::size_t i = 0; i < got.pixels.size(); ++i) {
            max_diff = std::max(max_diff, std::abs(got.pixels[i] - want.pixels[i]));
            spread = std::max(spread, std::abs(want.pixels[i] - want.pixels[0]));
        }
        EXPECT_EQ(max_diff, 0.0f);
        EXPECT_GT(spread, 0.05f);
    };
    compare("the frame set_scene uploaded for");
    rs.pack_channels = false;  // the metallic-roughness and normal maps as stored: decoded again
    compare("channels not packed");
    rs.pack_channels = true;
    rs.debug = DebugChannel::BaseColor;
    compare("debug view: the base colour as stored");
    rs.debug = DebugChannel::Occlusion;
    compare("debug view: the occlusion (never released)");
    // The scene's images stay released: what was decoded again is the renderer's own copy.
    EXPECT_TRUE(released.images[0].released());
}

// A material that reads more maps than the texture units hold: with the limit at the 16 units
// OpenGL 3.3 and ES 3.0 guarantee, its last maps in MaterialMap order go unread (the newest
// extensions' first), with no GL error, and the frame is the one of the material without them.
TEST_F(RenderTargets, MapsPastTheTextureUnitsGoUnread) {
    if (!start()) GTEST_SKIP() << why_;
    if (context_->capabilities().max_fragment_texture_units < 20)
        GTEST_SKIP() << "the context has " << context_->capabilities().max_fragment_texture_units
                     << " fragment texture units; the reference frame needs 20";
    // Every map but specular-glossiness's (19), with transmission: the occlusion is read from
    // the metallic-roughness texture (one texture: the same image and UV set), so 18 textures +
    // the transmitted scene and the split-sum table (no environment) = 20 units. At 16 the last
    // four go, in their pairs: diffuse transmission's two maps and iridescence's two.
    auto everything = [] {
        Material m;
        TextureSlot slot;
        slot.texture = 0;
        auto next = [&] {
            TextureSlot s = slot;
            slot.texture = (slot.texture + 1) % 4;
            return s;
        };
        m.base_color = next();
        m.metallic_roughness = next();
        m.normal = next();
        m.occlusion = next();
        m.emissive = next();
        m.emissive_factor = glm::vec3(0.3f);
        m.specular = SpecularExt{1.0f, next(), glm::vec3(1.0f), next()};
        m.clearcoat = ClearcoatExt{.clearcoat_factor = 0.5f, .clearcoat_texture = next(),
                                   .clearcoat_roughness_texture = next(), .clearcoat_normal_texture = next()};
        m.sheen = SheenExt{.sheen_color_factor = glm::vec3(0.5f), .sheen_color_texture = next(),
                           .sheen_roughness_texture = next()};
        m.transmission = TransmissionExt{.transmission_factor = 0.5f, .transmission_texture = next()};
        m.volume = VolumeExt{.thickness_factor = 0.1f, .thickness_texture = next()};
        m.anisotropy = AnisotropyExt{.anisotropy_strength = 0.5f, .anisotropy_texture = next()};
        m.iridescence = IridescenceExt{.iridescence_factor = 0.5f, .iridescence_texture = next(),
                                       .iridescence_thickness_texture = next()};
        m.diffuse_transmission = DiffuseTransmissionExt{.diffuse_transmission_factor = 0.5f,
                                                        .diffuse_transmission_texture = next(),
                                                        .diffuse_transmission_color_texture = next()};
        return m;
    };
    auto scene_with = [](const Material& m) {
        Primitive p = make_uv_sphere(32, 16);
        EXPECT_TRUE(generate_tangents(p, 0));
        p.material = 0;
        Scene s = make_single_primitive_scene(std::move(p), {m});
        s.images = {{"a", noise_image(1)}, {"b", noise_image(2)}, {"c", noise_image(3)}, {"d", noise_image(4)}};
        s.textures = {{0, {}}, {1, {}}, {2, {}}, {3, {}}};
        return s;
    };
    auto render = [&](const Scene& scene, int units, FrameStats& stats) {
        RenderSettings rs;
        rs.width = rs.height = 64;
        rs.ambient = glm::vec3(0.5f);
        rs.max_texture_units = units;
        Renderer renderer(*context_);
        renderer.set_scene(scene);
        CameraSetup cam = orbit_camera(scene_bounds(scene, flatten(scene)), {}, rs.width, rs.height);
        return renderer.render(cam, default_lights(), rs, &stats);
    };
    const Material full = everything();
    Material without = full;  // the four last maps in MaterialMap order, by hand
    without.iridescence->iridescence_texture = {};
    without.iridescence->iridescence_thickness_texture = {};
    without.diffuse_transmission->diffuse_transmission_texture = {};
    without.diffuse_transmission->diffuse_transmission_color_texture = {};
    FrameStats limited_stats, unlimited_stats, reference_stats;
    const ImageF limited = render(scene_with(full), 16, limited_stats);
    const ImageF unlimited = render(scene_with(full), 0, unlimited_stats);
    const ImageF reference = render(scene_with(without), 0, reference_stats);
    EXPECT_EQ(limited_stats.gl_errors, "");
    EXPECT_EQ(unlimited_stats.gl_errors, "");
    EXPECT_GE(limited_stats.unit_limited_draws, 1);
    EXPECT_EQ(unlimited_stats.unit_limited_draws, 0);
    EXPECT_EQ(reference_stats.unit_limited_draws, 0);
    float limited_vs_reference = 0.0f, limited_vs_unlimited = 0.0f;
    for (std::size_t i = 0; i < limited.pixels.size(); ++i) {
        limited_vs_reference = std::max(limited_vs_reference, std::abs(limited.pixels[i] - reference.pixels[i]));
        limited_vs_unlimited = std::max(limited_vs_unlimited, std::abs(limited.pixels[i] - unlimited.pixels[i]));
    }
    std::printf("16 units: %d draws limited; against the material without its last four maps: max difference %g; "
                "against all maps read: %g\n",
                limited_stats.unit_limited_draws, double(limited_vs_reference), double(limited_vs_unlimited));
    EXPECT_EQ(limited_vs_reference, 0.0f);
    EXPECT_GT(limited_vs_unlimited, 0.0f);  // the maps did change the frame
}

// Contexts share the process's EGL display: one going (its destructor) must leave the others
// working, in any order (`fresnel batch --jobs N` ends its workers' contexts on their threads
// as each finishes; the first used to terminate the display under the rest).
TEST(HeadlessContexts, OneGoingLeavesTheOthersWorking) {
    gpu::ContextOptions co;
    co.surface_width = 4;
    co.surface_height = 4;
    std::string why;
    auto first = test_support::try_headless_context(why, co);
    if (!first) GTEST_SKIP() << "no EGL pbuffer: " << why;
    std::unique_ptr<gpu::Context> second = gpu::create_headless_context(co);  // current now
    first.reset();  // leaves the second current
    gpu::Device device;
    device.bind_framebuffer(nullptr);
    device.viewport(0, 0, 4, 4);
    device.clear(glm::vec4(0.25f, 0.5f, 0.75f, 1.0f), false);
    std::vector<std::uint8_t> px = device.read_default_rgba8(1, 1, 1, 1);
    ASSERT_EQ(px.size(), 4u);
    EXPECT_NEAR(px[0], 64, 1);
    EXPECT_NEAR(px[1], 128, 1);
    EXPECT_NEAR(px[2], 191, 1);
    EXPECT_EQ(device.take_errors(), "");
    ASSERT_NO_THROW(second->make_current());
    // And a third made after the first went, with the second still there.
    EXPECT_NO_THROW(gpu::create_headless_context(co));
}
