#pragma once
// RAII wrappers for GL objects, limited to OpenGL 3.3 core ∩ OpenGL ES 3.0.
// Each owns one GL name; moving transfers it, destruction deletes it.
#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "fresnel/core/sampler.h"

namespace fresnel::gpu {

class Handle {
public:
    Handle() = default;
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    Handle(Handle&& o) noexcept : id_(o.id_) { o.id_ = 0; }
    Handle& operator=(Handle&& o) noexcept {
        std::swap(id_, o.id_);
        return *this;
    }
    unsigned id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }

protected:
    unsigned id_ = 0;
};

enum class BufferKind { Vertex, Index };

class Buffer : public Handle {
public:
    Buffer() = default;
    Buffer(BufferKind kind, const void* data, std::size_t bytes);
    Buffer(Buffer&&) noexcept = default;
    Buffer& operator=(Buffer&&) noexcept = default;
    ~Buffer();
    BufferKind kind() const { return kind_; }
    // Replaces the whole contents with `bytes` bytes (new storage: draws already submitted keep
    // reading the old; a per-frame stream, as the renderer's instance matrices).
    void replace(const void* data, std::size_t bytes);

private:
    BufferKind kind_ = BufferKind::Vertex;
};

// A uniform buffer: the storage of a std140 uniform block (OpenGL 3.1+, OpenGL ES 3.0).
class UniformBuffer : public Handle {
public:
    UniformBuffer() = default;
    explicit UniformBuffer(std::size_t bytes);  // contents undefined until update()
    UniformBuffer(UniformBuffer&&) noexcept = default;
    UniformBuffer& operator=(UniformBuffer&&) noexcept = default;
    ~UniformBuffer();
    std::size_t size() const { return size_; }
    // Replaces the first `bytes` bytes (at most size()).
    void update(const void* data, std::size_t bytes);
    // Binds the buffer to uniform binding point `binding` (Program::bind_uniform_block).
    void bind(unsigned binding) const;

private:
    std::size_t size_ = 0;
};

// The per-instance attributes of instanced mesh draws (Program binds them at link):
// "a_instance_model" (mat4: locations 8..11) and "a_instance_normal" (mat3: 12..14).
constexpr unsigned kInstanceModelLocation = 8, kInstanceNormalLocation = 12;
// Baked per-vertex occlusion ("a_occlusion", a vec4, location 15: the last of the 16 attributes
// OpenGL ES 3.0 guarantees). A mesh draw without it leaves the array disabled: the attribute
// then reads the default (0, 0, 0, 1), visibility 1.
constexpr unsigned kOcclusionLocation = 15;

// A vertex array: float attributes from buffers, optional index buffer (uint32).
class VertexArray : public Handle {
public:
    VertexArray();
    VertexArray(VertexArray&&) noexcept = default;
    VertexArray& operator=(VertexArray&&) noexcept = default;
    ~VertexArray();
    // Binds `buffer` (tightly packed floats, `components` per vertex) to attribute `location`.
    void set_attribute(unsigned location, const Buffer& buffer, int components);
    // Binds `components` floats at byte `offset` of each `stride`-byte record of `buffer` to
    // attribute `location`, advanced once per instance (glVertexAttribDivisor 1: instanced draws).
    void set_instance_attribute(unsigned location, const Buffer& buffer, int components, std::size_t stride,
                                std::size_t offset);
    void set_indices(const Buffer& buffer);
    // Turns attribute `location`'s array off: the attribute reads its constant default value.
    void disable_attribute(unsigned location);
};

enum class TextureFormat { RGBA8, SRGB8_ALPHA8, RGBA16F, RGBA32F, RG16F, R8 };

// Sampling of a texture (translated to GL in set_sampler). Default: trilinear, repeating
// in s and t, clamped in r (cube maps).
struct SamplerState {
    Filter min_filter = Filter::Linear;      // within a mip level
    MipmapMode mipmap = MipmapMode::Linear;  // across mip levels (None: level 0 only)
    Filter mag_filter = Filter::Linear;
    Wrap wrap_s = Wrap::Repeat, wrap_t = Wrap::Repeat, wrap_r = Wrap::ClampToEdge;
    // Anisotropic filtering (EXT_texture_filter_anisotropic, applied only where the
    // driver has it), clamped to the driver's maximum. 1 = off.
    float max_anisotropy = 1.0f;
    // `filter` both ways, no mip levels, clamped to the edge (LUTs, render targets).
    static SamplerState clamped(Filter filter) {
        SamplerState s;
        s.min_filter = s.mag_filter = filter;
        s.mipmap = MipmapMode::None;
        s.wrap_s = s.wrap_t = s.wrap_r = Wrap::ClampToEdge;
        return s;
    }
};

// One level of a mip chain for Texture::create_2d_levels (tightly packed texels).
struct MipLevel {
    int width = 0, height = 0;
    const void* data = nullptr;
};

class Texture : public Handle {
public:
    enum class Kind { Tex2D, Cube, Tex2DMultisample, Tex2DArray };
    Texture() = default;
    // Uploads a 2D image (rows top to bottom as stored; data may be null). `mipmaps` generates the chain.
    static Texture create_2d(int width, int height, TextureFormat format, const void* data, bool mipmaps);
    // Uploads a 2D image with its mip chain made on the CPU (levels[0] is the base);
    // the driver generates nothing. `immutable_storage` (Capabilities::texture_storage)
    // allocates the chain once with glTexStorage2D.
    static Texture create_2d_levels(TextureFormat format, std::span<const MipLevel> levels,
                                    bool immutable_storage = false);
    // A multisampled colour target a shader reads with texelFetch (OpenGL 3.2+; not in
    // OpenGL ES 3.0, where Capabilities::multisample_textures is false).
    static Texture create_2d_multisample(int width, int height, TextureFormat format, int samples);
    // A cube map with `levels` mip levels (data uploaded later with upload_cube_face).
    // `immutable_storage` (Capabilities::texture_storage): glTexStorage2D, allocated once.
    static Texture create_cube(int size, TextureFormat format, int levels, bool immutable_storage = false);
    // A 24-bit depth texture to render into (Framebuffer::attach_depth) and read with a
    // sampler2DShadow: comparison mode LEQUAL, linear filtering (the 2x2 percentage-closer
    // filter of OpenGL 3.3 and ES 3.0), clamped to the edge. `compare` false: read as depth
    // values through a sampler2D, nearest texel (screen-space occlusion).
    static Texture create_depth_2d(int width, int height, bool compare = true);
    void upload_cube_face(int face, int level, int size, const float* rgba);
    // Data textures: RGBA32F tables a shader reads texel by texel with texelFetch (joint
    // matrices, morph target displacements), never filtered: one level, NEAREST (a float
    // texture that filters linearly is incomplete on OpenGL ES 3.0 without
    // OES_texture_float_linear), clamped. `rgba` (4 floats a texel, rows then layers) may be
    // null. A 2D array has `layers` layers (GL_MAX_ARRAY_TEXTURE_LAYERS: 256 or more on
    // OpenGL 3.3 and ES 3.0); sides up to GL_MAX_TEXTURE_SIZE (2048 or more).
    static Texture create_data_2d(int width, int height, const float* rgba);
    static Texture create_data_2d_array(int width, int height, int layers, const float* rgba);
    // Replaces a rectangle of level 0 of a 2D texture in place (glTexSubImage2D: nothing is
    // allocated again), `data` tightly packed in the texture's format.
    void update_2d(int x, int y, int width, int height, const void* data);
    // Where the format cannot filter linearly (RGBA32F on OpenGL ES 3.0 without
    // OES_texture_float_linear, where a LINEAR float texture is incomplete and samples as zero),
    // LINEAR filters become NEAREST: filters_linearly() tells which one the texture got.
    void set_sampler(const SamplerState& s);
    bool filters_linearly() const { return linear_; }
    // Regenerates levels 1.. of a 2D texture from level 0 (glGenerateMipmap), e.g. after
    // rendering into it.
    void generate_mipmaps();
    Texture(Texture&&) noexcept = default;
    Texture& operator=(Texture&&) noexcept = default;
    ~Texture();
    int width() const { return width_; }
    int height() const { return height_; }
    int layers() const { return layers_; }  // a 2D array's; 1 for the others
    Kind kind() const { return kind_; }
    TextureFormat format() const { return format_; }
    // The texel storage it was created with: every mip level, face and sample (what the
    // statistics panel reports as texture memory; drivers may pad).
    std::size_t bytes() const { return bytes_; }

private:
    std::size_t bytes_ = 0;
    int width_ = 0, height_ = 0, layers_ = 1;
    Kind kind_ = Kind::Tex2D;
    TextureFormat format_ = TextureFormat::RGBA8;
    bool linear_ = true;  // the magnification filter set: LINEAR (else NEAREST)
};

// A sampler object (OpenGL 3.3, OpenGL ES 3.0): sampling state bound to a texture unit
// (Device::bind_texture's `sampler`) in place of the texture's own, so that one texture can be
// read two ways at once from two units.
class SamplerObject : public Handle {
public:
    SamplerObject() = default;
    // A depth texture read as its depth values through a sampler2D (no comparison, the nearest
    // texel, clamped to the edge): beside its sampler2DShadow reads (create_depth_2d), the
    // blocker search of contact-hardening shadows.
    static SamplerObject depth_values();
    SamplerObject(SamplerObject&&) noexcept = default;
    SamplerObject& operator=(SamplerObject&&) noexcept = default;
    ~SamplerObject();
};

enum class RenderbufferFormat { RGBA16F, RGBA32F, RGBA8, Depth24 };

class Renderbuffer : public Handle {
public:
    Renderbuffer() = default;
    Renderbuffer(int width, int height, RenderbufferFormat format, int samples);
    Renderbuffer(Renderbuffer&&) noexcept = default;
    Renderbuffer& operator=(Renderbuffer&&) noexcept = default;
    ~Renderbuffer();
    int samples() const { return samples_; }
    RenderbufferFormat format() const { return format_; }

private:
    int samples_ = 0;
    RenderbufferFormat format_ = RenderbufferFormat::RGBA16F;
};

// The GPU time of the commands between begin() and end() (GL_TIME_ELAPSED). Only where
// Capabilities::timer_queries says so (OpenGL 3.3; not ES 3.0): check before constructing.
class TimerQuery : public Handle {
public:
    TimerQuery();
    TimerQuery(TimerQuery&&) noexcept = default;
    TimerQuery& operator=(TimerQuery&&) noexcept = default;
    ~TimerQuery();
    void begin();
    void end();
    // The elapsed milliseconds once the GPU has them (never waits); false before.
    bool result_ms(double& ms) const;
};

class Framebuffer : public Handle {
public:
    Framebuffer();
    Framebuffer(Framebuffer&&) noexcept = default;
    Framebuffer& operator=(Framebuffer&&) noexcept = default;
    ~Framebuffer();
    void attach_color(const Texture& texture);
    void attach_color(const Renderbuffer& rb);
    void attach_depth(const Renderbuffer& rb);
    // A depth texture (Texture::create_depth_2d) as the only attachment: no colour is drawn
    // or read (draw and read buffers NONE).
    void attach_depth(const Texture& depth);
    // Throws fresnel::Error when the framebuffer is incomplete.
    void check() const;
    // True when the colour attachment is fixed-point (RGBA8, sRGB, R8): read back as bytes.
    bool color_normalized() const { return color_normalized_; }

private:
    bool color_normalized_ = false;
};

// GL_MAX_SAMPLES of the current context (Context::capabilities() also has the
// largest count for float colour targets, which may be lower on OpenGL ES).
int max_samples();

class Program : public Handle {
public:
    Program() = default;
    // Compiles and links; throws fresnel::Error naming `name` with the driver's log.
    Program(const std::string& name, const std::string& vertex_source, const std::string& fragment_source);
    Program(Program&&) noexcept = default;
    Program& operator=(Program&&) noexcept = default;
    ~Program();
    void use() const;
    // The location of an active uniform (arrays by their bare name), -1 for none. Every
    // location is read once, when the program is linked; looking one up allocates nothing.
    int location(std::string_view uniform) const;
    // Setters on the current program (call use() first); unknown names are ignored.
    void set(std::string_view name, int v) const;
    void set(std::string_view name, float v) const;
    void set(std::string_view name, glm::vec2 v) const;
    void set(std::string_view name, glm::vec3 v) const;
    void set(std::string_view name, glm::vec4 v) const;
    void set(std::string_view name, const glm::mat3& v) const;
    void set(std::string_view name, const glm::mat4& v) const;
    void set(std::string_view name, std::span<const glm::vec4> v) const;
    void set(std::string_view name, std::span<const glm::vec3> v) const;
    void set(std::string_view name, std::span<const glm::mat4> v) const;  // a mat4 array (joint matrices)
    void set(std::string_view name, std::span<const float> v) const;      // a float array (morph weights)
    // Connects the uniform block `block` (if the program has it) to buffer binding point
    // `binding` (UniformBuffer::bind). GLSL ES 3.00 has no layout(binding = N) for blocks.
    void bind_uniform_block(const char* block, unsigned binding) const;
    // Byte offsets of the named uniform block members, -1 for a name the program lacks
    // (tests check a C++ mirror of a std140 block against them).
    std::vector<int> uniform_offsets(const std::vector<std::string>& names) const;
    // The size in bytes of uniform block `block` as laid out, 0 when the program lacks it.
    int uniform_block_size(const char* block) const;

private:
    std::map<std::string, int, std::less<>> locations_;
};

}  // namespace fresnel::gpu
