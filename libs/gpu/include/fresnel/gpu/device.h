#pragma once
// Pipeline state, draws, clears, blits and read-back on the current context.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fresnel/gpu/resources.h"

namespace fresnel::gpu {

enum class Cull { None, Back };
enum class Blend { None, PremultipliedOver, AlphaOver };
enum class Primitive { Points, Lines, LineLoop, LineStrip, Triangles };

struct PipelineState {
    bool depth_test = true;
    bool depth_write = true;
    Cull cull = Cull::Back;
    Blend blend = Blend::None;
    bool sample_alpha_to_coverage = false;
    bool front_ccw = true;  // false for nodes whose world matrix mirrors (negative determinant)
    // glPolygonOffset(factor, units) when either is non-zero (shadow maps' slope-scaled bias).
    float offset_factor = 0.0f, offset_units = 0.0f;
};

// The GL objects alive in the current context, as the driver reports them (glIs* over the
// names it has handed out), for leak checks: a scene opened and closed leaves these unchanged.
struct LiveObjects {
    int buffers = 0, vertex_arrays = 0, textures = 0, renderbuffers = 0, framebuffers = 0, programs = 0,
        shaders = 0;
    int total() const { return buffers + vertex_arrays + textures + renderbuffers + framebuffers + programs + shaders; }
};

class Device {
public:
    void bind_framebuffer(const Framebuffer* fb);  // nullptr = default framebuffer
    void viewport(int x, int y, int width, int height);
    // Limits writes to a rectangle (scissor test on) / lifts the limit.
    void scissor(int x, int y, int width, int height);
    void no_scissor();
    void clear(glm::vec4 color, bool depth = true);
    void apply(const PipelineState& state);
    // Binds `texture` to `unit`, sampled by its own state or, when given, by `sampler`'s (the
    // unit's sampler object is unbound again by the next bind_texture without one).
    void bind_texture(int unit, const Texture& texture, const SamplerObject* sampler = nullptr);
    void draw(const VertexArray& vao, Primitive mode, int count, bool indexed);
    // `instances` copies of the same draw (glDraw*Instanced; the VAO's per-instance attributes
    // step once per copy: VertexArray::set_instance_attribute).
    void draw_instanced(const VertexArray& vao, Primitive mode, int count, bool indexed, int instances);
    // Draws a full-screen triangle (the vertex shader makes positions from gl_VertexID).
    void draw_fullscreen();
    void blit_color(const Framebuffer& src, const Framebuffer& dst, int width, int height);
    // Reads RGBA float pixels of the bound read framebuffer, rows bottom to top (GL order).
    std::vector<float> read_rgba32f(const Framebuffer& fb, int width, int height);
    // Reads 8-bit RGBA of an RGBA8 framebuffer's colour, rows bottom to top (GL order).
    std::vector<std::uint8_t> read_rgba8(const Framebuffer& fb, int width, int height);
    // Reads 8-bit RGBA from the default framebuffer (a window's, or a pbuffer's), rows bottom to top.
    std::vector<std::uint8_t> read_default_rgba8(int x, int y, int width, int height);
    // Counts the live objects (a few ms: one glIs* call per name handed out so far).
    LiveObjects live_objects();
    // Returns "" or the names of pending GL errors (clears them).
    std::string take_errors();
    void finish();

private:
    VertexArray& empty_vao();
    std::uint64_t units_with_sampler_ = 0;  // units 0..63 that have a sampler object bound
    std::unique_ptr<VertexArray> empty_vao_;
};

}  // namespace fresnel::gpu
