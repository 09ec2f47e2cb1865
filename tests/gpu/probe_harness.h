#pragma once
// What the shader-probe suites share (brdf, legacy shading, material, transmission): a probe
// fragment shader evaluates one case per pixel of a float target, reading the case's inputs
// from RGBA32F texels laid side by side, and the test compares each result with the C++ twin.
#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "fresnel/gpu/context.h"
#include "fresnel/gpu/device.h"
#include "fresnel/gpu/resources.h"
#include "details/shader_library.h"

namespace fresnel::test {

// The input texels of `count` cases, `per_case` texels each side by side, `per_row` cases a row
// (rows of per_row * per_case texels): texel(i, k) is case i's k-th texel.
template <class Texel>
std::vector<float> pack_case_texels(std::size_t count, int per_case, int per_row, Texel&& texel) {
    const std::size_t row_texels = std::size_t(per_row) * std::size_t(per_case);
    const std::size_t rows = (count + std::size_t(per_row) - 1) / std::size_t(per_row);
    std::vector<float> texels(row_texels * rows * 4, 0.0f);
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t x = i % std::size_t(per_row), y = i / std::size_t(per_row);
        for (int k = 0; k < per_case; ++k) {
            const glm::vec4 t = texel(i, k);
            float* out = &texels[(y * row_texels + x * std::size_t(per_case) + std::size_t(k)) * 4];
            for (int c = 0; c < 4; ++c) out[c] = t[c];
        }
    }
    return texels;
}

// How far a value moves when the directions it is computed from move by float rounding: `f(move)`
// evaluates it with each of its directions passed through move(direction, i), and the band is
// the largest change over six moves, along each axis both ways, of 4e-7 (a few ulps) with
// direction i along axis (k + i) mod 3 and the sign alternating with i. The GPU's directions
// differ from the C++ ones by that much (normalised there), and near the GGX peak of a glossy
// lobe that alone moves a value by up to 1e-3 of itself, in either implementation; the shading
// suites allow the band on top of their relative tolerance.
template <class F>
glm::vec3 rounding_band(F&& f) {
    const glm::vec3 base = f([](glm::vec3 d, int) { return d; });
    glm::vec3 band(0.0f);
    for (int k = 0; k < 6; ++k) {
        const float step = k < 3 ? 4e-7f : -4e-7f;
        band = glm::max(band, glm::abs(f([&](glm::vec3 d, int i) {
                                           glm::vec3 offset(0.0f);
                                           offset[(k + i) % 3] = i % 2 ? -step : step;
                                           return glm::normalize(d + offset);
                                       }) -
                                       base));
    }
    return band;
}

// The w x h RGBA32F target a probe draws into, one result a pixel (row-major from the bottom
// row, as the cases are packed).
class ProbeTarget {
public:
    ProbeTarget(int w, int h)
        : w_(w), h_(h), color_(gpu::Texture::create_2d(w, h, gpu::TextureFormat::RGBA32F, nullptr, false)) {
        fb_.attach_color(color_);
        fb_.check();
    }
    // Binds the target with its viewport, no depth test and no culling (the full-screen draw).
    void bind(gpu::Device& device) {
        device.bind_framebuffer(&fb_);
        device.viewport(0, 0, w_, h_);
        gpu::PipelineState state;
        state.depth_test = false;
        state.depth_write = false;
        state.cull = gpu::Cull::None;
        device.apply(state);
    }
    // Clears to a sentinel (alpha -7: a pixel the draw misses keeps it), draws the bound program
    // over the target and reads back the first `count` results. Leaves the default framebuffer
    // bound (read_rgba32f does).
    std::vector<glm::vec4> draw(gpu::Device& device, std::size_t count) {
        device.bind_framebuffer(&fb_);
        device.clear(glm::vec4(-7.0f), false);
        device.draw_fullscreen();
        const std::vector<float> px = device.read_rgba32f(fb_, w_, h_);
        std::vector<glm::vec4> out(count);
        for (std::size_t i = 0; i < count; ++i) out[i] = glm::vec4(px[i * 4], px[i * 4 + 1], px[i * 4 + 2], px[i * 4 + 3]);
        return out;
    }
    // How many results have an alpha other than 1 (the probes write 1 where they ran).
    static int unwritten(const std::vector<glm::vec4>& results) {
        int n = 0;
        for (const glm::vec4& r : results) n += r.w != 1.0f;
        return n;
    }

private:
    int w_, h_;
    gpu::Texture color_;
    gpu::Framebuffer fb_;
};

// Draws `fragment` (with fullscreen.vert and `defines`) over `cases` of N texels each, `grid`
// cases a row, with the texels on unit 0 as u_inputs and u_mode = `mode`: one result a case.
// Fails the test on GL errors or pixels the draw did not write.
template <std::size_t N>
std::vector<glm::vec4> run_mode_probe(ShaderLibrary& library, const std::string& fragment, int mode,
                                      const std::vector<std::array<glm::vec4, N>>& cases, int grid,
                                      const std::vector<std::string>& defines = {}) {
    const int h = int((cases.size() + std::size_t(grid) - 1) / std::size_t(grid));
    const std::vector<float> texels =
        pack_case_texels(cases.size(), int(N), grid, [&](std::size_t i, int k) { return cases[i][std::size_t(k)]; });
    gpu::Device device;
    gpu::Texture inputs = gpu::Texture::create_2d(int(N) * grid, h, gpu::TextureFormat::RGBA32F, texels.data(), false);
    ProbeTarget target(grid, h);
    target.bind(device);
    const gpu::Program& program = library.get("fullscreen.vert", fragment, defines);
    program.use();
    program.set("u_inputs", 0);
    program.set("u_mode", mode);
    device.bind_texture(0, inputs);
    std::vector<glm::vec4> out = target.draw(device, cases.size());
    EXPECT_EQ(device.take_errors(), "") << "GL errors in " << fragment << " mode " << mode;
    EXPECT_EQ(ProbeTarget::unwritten(out), 0) << "pixels not written by " << fragment << " (mode " << mode << ")";
    return out;
}

// A suite with one headless OpenGL context (EGL, llvmpipe in CI) and one shader library for all
// its tests; a test fails at its start when no context could be made.
class ProbeSuite : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        try {
            context_ = gpu::create_headless_context();
        } catch (const std::exception& e) {
            context_error_ = e.what();
        }
    }
    static void TearDownTestSuite() {
        library_.reset();  // programs before the context that owns them
        context_.reset();
    }
    void SetUp() override {
        ASSERT_TRUE(context_) << "no headless OpenGL context (EGL/llvmpipe): " << context_error_;
        context_->make_current();
        if (!library_) library_ = std::make_unique<ShaderLibrary>(glsl_target(context_->api()));
    }
    static ShaderLibrary& library() { return *library_; }

    static inline std::unique_ptr<gpu::Context> context_;
    static inline std::string context_error_;
    static inline std::unique_ptr<ShaderLibrary> library_;
};

}  // namespace fresnel::test
