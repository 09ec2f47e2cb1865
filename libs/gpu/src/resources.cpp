#include "fresnel/gpu/resources.h"

#include "gl.h"

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>

#include "fresnel/core/error.h"

namespace fresnel::gpu {

Buffer::Buffer(BufferKind kind, const void* data, std::size_t bytes) : kind_(kind) {
    glGenBuffers(1, &id_);
    GLenum target = kind == BufferKind::Index ? GL_ELEMENT_ARRAY_BUFFER : GL_ARRAY_BUFFER;
    if (kind == BufferKind::Index) glBindVertexArray(0);  // do not disturb a bound VAO's index binding
    glBindBuffer(target, id_);
    glBufferData(target, GLsizeiptr(bytes), data, GL_STATIC_DRAW);
    glBindBuffer(target, 0);
}
void Buffer::replace(const void* data, std::size_t bytes) {
    const GLenum target = kind_ == BufferKind::Index ? GL_ELEMENT_ARRAY_BUFFER : GL_ARRAY_BUFFER;
    if (kind_ == BufferKind::Index) glBindVertexArray(0);
    glBindBuffer(target, id_);
    glBufferData(target, GLsizeiptr(bytes), data, GL_STREAM_DRAW);
    glBindBuffer(target, 0);
}
Buffer::~Buffer() {
    if (id_) glDeleteBuffers(1, &id_);
}

UniformBuffer::UniformBuffer(std::size_t bytes) : size_(bytes) {
    glGenBuffers(1, &id_);
    glBindBuffer(GL_UNIFORM_BUFFER, id_);
    glBufferData(GL_UNIFORM_BUFFER, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_UNIFORM_BUFFER, 0);
}
UniformBuffer::~UniformBuffer() {
    if (id_) glDeleteBuffers(1, &id_);
}
void UniformBuffer::update(const void* data, std::size_t bytes) {
    glBindBuffer(GL_UNIFORM_BUFFER, id_);
    glBufferSubData(GL_UNIFORM_BUFFER, 0, GLsizeiptr(std::min(bytes, size_)), data);
    glBindBuffer(GL_UNIFORM_BUFFER, 0);
}
void UniformBuffer::bind(unsigned binding) const { glBindBufferBase(GL_UNIFORM_BUFFER, binding, id_); }

VertexArray::VertexArray() { glGenVertexArrays(1, &id_); }
VertexArray::~VertexArray() {
    if (id_) glDeleteVertexArrays(1, &id_);
}
void VertexArray::set_attribute(unsigned location, const Buffer& buffer, int components) {
    glBindVertexArray(id_);
    glBindBuffer(GL_ARRAY_BUFFER, buffer.id());
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}
void VertexArray::set_instance_attribute(unsigned location, const Buffer& buffer, int components, std::size_t stride,
                                         std::size_t offset) {
    glBindVertexArray(id_);
    glBindBuffer(GL_ARRAY_BUFFER, buffer.id());
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, GLsizei(stride),
                          reinterpret_cast<const void*>(offset));
    glVertexAttribDivisor(location, 1);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}
void VertexArray::disable_attribute(unsigned location) {
    glBindVertexArray(id_);
    glDisableVertexAttribArray(location);
    glBindVertexArray(0);
}
void VertexArray::set_indices(const Buffer& buffer) {
    glBindVertexArray(id_);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffer.id());
    glBindVertexArray(0);
}

namespace {
struct FormatInfo {
    GLint internal;
    GLenum format, type;
};
FormatInfo info(TextureFormat f) {
    switch (f) {
        case TextureFormat::RGBA8: return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
        case TextureFormat::SRGB8_ALPHA8: return {GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE};
        case TextureFormat::RGBA16F: return {GL_RGBA16F, GL_RGBA, GL_FLOAT};
        case TextureFormat::RGBA32F: return {GL_RGBA32F, GL_RGBA, GL_FLOAT};
        case TextureFormat::RG16F: return {GL_RG16F, GL_RG, GL_FLOAT};
        case TextureFormat::R8: return {GL_R8, GL_RED, GL_UNSIGNED_BYTE};
    }
    return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
}
std::size_t texel_bytes(TextureFormat f) {
    switch (f) {
        case TextureFormat::RGBA8:
        case TextureFormat::SRGB8_ALPHA8:
        case TextureFormat::RG16F: return 4;
        case TextureFormat::RGBA16F: return 8;
        case TextureFormat::RGBA32F: return 16;
        case TextureFormat::R8: return 1;
    }
    return 4;
}
// Texels of a w x h image and, with `chain`, its mip levels down to 1 x 1.
std::size_t texels(int w, int h, bool chain) {
    std::size_t n = 0;
    for (;;) {
        n += std::size_t(w) * std::size_t(h);
        if (!chain || (w == 1 && h == 1)) return n;
        w = std::max(1, w / 2);
        h = std::max(1, h / 2);
    }
}
// 32-bit float textures filter linearly on GL 3.3; on ES 3.0 only with OES_texture_float_linear
// (without it a LINEAR-filtered RGBA32F texture is incomplete and samples as zero).
bool filterable(TextureFormat f) {
    if (f != TextureFormat::RGBA32F || gl::is_desktop()) return true;
    return gl::has_extension("GL_OES_texture_float_linear");
}
GLint gl_filter(Filter f) { return f == Filter::Nearest ? GL_NEAREST : GL_LINEAR; }
GLint gl_min_filter(Filter f, MipmapMode m) {
    switch (m) {
        case MipmapMode::None: return gl_filter(f);
        case MipmapMode::Nearest: return f == Filter::Nearest ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR_MIPMAP_NEAREST;
        case MipmapMode::Linear: break;
    }
    return f == Filter::Nearest ? GL_NEAREST_MIPMAP_LINEAR : GL_LINEAR_MIPMAP_LINEAR;
}
// Sets the bound texture's filters, LINEAR ones made NEAREST where the format cannot filter
// linearly (filterable); returns whether it filters linearly. The one place texture filters are set.
bool set_filters(GLenum target, TextureFormat format, Filter min_filter, MipmapMode mipmap, Filter mag_filter) {
    if (!filterable(format)) {
        min_filter = mag_filter = Filter::Nearest;
        if (mipmap != MipmapMode::None) mipmap = MipmapMode::Nearest;
    }
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, gl_min_filter(min_filter, mipmap));
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, gl_filter(mag_filter));
    return mag_filter == Filter::Linear;
}
GLint gl_wrap(Wrap w) {
    switch (w) {
        case Wrap::ClampToEdge: return GL_CLAMP_TO_EDGE;
        case Wrap::MirroredRepeat: return GL_MIRRORED_REPEAT;
        case Wrap::Repeat: break;
    }
    return GL_REPEAT;
}
}  // namespace

Texture Texture::create_2d(int width, int height, TextureFormat format, const void* data, bool mipmaps) {
    Texture t;
    t.width_ = width;
    t.height_ = height;
    t.format_ = format;
    glGenTextures(1, &t.id_);
    glBindTexture(GL_TEXTURE_2D, t.id_);
    FormatInfo fi = info(format);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, fi.internal, width, height, 0, fi.format, fi.type, data);
    if (mipmaps) glGenerateMipmap(GL_TEXTURE_2D);
    t.bytes_ = texels(width, height, mipmaps) * texel_bytes(format);
    t.linear_ = set_filters(GL_TEXTURE_2D, format, Filter::Linear, mipmaps ? MipmapMode::Linear : MipmapMode::None,
                            Filter::Linear);
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
}

Texture Texture::create_depth_2d(int width, int height, bool compare) {
    Texture t;
    t.width_ = width;
    t.height_ = height;
    t.format_ = TextureFormat::R8;  // not a colour format: bytes() below is what counts
    glGenTextures(1, &t.id_);
    glBindTexture(GL_TEXTURE_2D, t.id_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, width, height, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT,
                 nullptr);
    // With comparison: linear (sampler2DShadow's 2x2 filter); without: read as depth values,
    // which ES 3.0 filters only by the nearest texel.
    const GLint filter = compare ? GL_LINEAR : GL_NEAREST;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (compare) {
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }
    t.bytes_ = std::size_t(width) * std::size_t(height) * 4;
    t.linear_ = true;
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
}

SamplerObject SamplerObject::depth_values() {
    SamplerObject o;
    glGenSamplers(1, &o.id_);
    glSamplerParameteri(o.id_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(o.id_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(o.id_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(o.id_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(o.id_, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    return o;
}

SamplerObject::~SamplerObject() {
    if (id_) glDeleteSamplers(1, &id_);
}

void Texture::generate_mipmaps() {
    glBindTexture(GL_TEXTURE_2D, id_);
    glGenerateMipmap(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, 0);
}

Texture Texture::create_2d_levels(TextureFormat format, std::span<const MipLevel> levels, bool immutable_storage) {
    Texture t;
    if (levels.empty()) return t;
    t.width_ = levels[0].width;
    t.height_ = levels[0].height;
    t.format_ = format;
    glGenTextures(1, &t.id_);
    glBindTexture(GL_TEXTURE_2D, t.id_);
    FormatInfo fi = info(format);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // With immutable storage the driver allocates the whole chain once; level by level,
    // Mesa keeps each level apart and copies them all into one tree at the first draw
    // (DamagedHelmet: ~60 MB more memory and a copy of 112 MB).
    if (immutable_storage)
        glTexStorage2D(GL_TEXTURE_2D, GLsizei(levels.size()), fi.internal, levels[0].width, levels[0].height);
    for (std::size_t l = 0; l < levels.size(); ++l) {
        if (immutable_storage)
            glTexSubImage2D(GL_TEXTURE_2D, GLint(l), 0, 0, levels[l].width, levels[l].height, fi.format, fi.type,
                            levels[l].data);
        else
            glTexImage2D(GL_TEXTURE_2D, GLint(l), fi.internal, levels[l].width, levels[l].height, 0, fi.format, fi.type,
                         levels[l].data);
        t.bytes_ += texels(levels[l].width, levels[l].height, false) * texel_bytes(format);
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, GLint(levels.size() - 1));
    t.linear_ = set_filters(GL_TEXTURE_2D, format, Filter::Linear,
                            levels.size() > 1 ? MipmapMode::Linear : MipmapMode::None, Filter::Linear);
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
}

Texture Texture::create_2d_multisample(int width, int height, TextureFormat format, int samples) {
    Texture t;
    t.width_ = width;
    t.height_ = height;
    t.format_ = format;
    t.kind_ = Kind::Tex2DMultisample;
    glGenTextures(1, &t.id_);
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, t.id_);
    // Fixed sample locations, as renderbuffers have: the depth renderbuffer attaches beside it.
    glTexImage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, samples, info(format).internal, width, height, GL_TRUE);
    t.bytes_ = texels(width, height, false) * texel_bytes(format) * std::size_t(std::max(samples, 1));
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
    return t;
}

Texture Texture::create_cube(int size, TextureFormat format, int levels, bool immutable_storage) {
    Texture t;
    t.width_ = t.height_ = size;
    t.kind_ = Kind::Cube;
    t.format_ = format;
    glGenTextures(1, &t.id_);
    glBindTexture(GL_TEXTURE_CUBE_MAP, t.id_);
    FormatInfo fi = info(format);
    if (immutable_storage) glTexStorage2D(GL_TEXTURE_CUBE_MAP, levels, fi.internal, size, size);
    for (int level = 0; level < levels; ++level) {
        for (int face = 0; face < 6 && !immutable_storage; ++face)
            glTexImage2D(GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face), level, fi.internal, std::max(1, size >> level),
                         std::max(1, size >> level), 0, fi.format, fi.type, nullptr);
        t.bytes_ += 6 * texels(std::max(1, size >> level), std::max(1, size >> level), false) * texel_bytes(format);
    }
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, levels - 1);
    t.linear_ = set_filters(GL_TEXTURE_CUBE_MAP, format, Filter::Linear, levels > 1 ? MipmapMode::Linear : MipmapMode::None,
                            Filter::Linear);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
    return t;
}

void Texture::upload_cube_face(int face, int level, int size, const float* rgba) {
    glBindTexture(GL_TEXTURE_CUBE_MAP, id_);
    FormatInfo fi = info(format_);
    glTexSubImage2D(GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face), level, 0, 0, size, size, GL_RGBA, GL_FLOAT, rgba);
    (void)fi;
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
}

Texture Texture::create_data_2d(int width, int height, const float* rgba) {
    Texture t;
    t.width_ = width;
    t.height_ = height;
    t.format_ = TextureFormat::RGBA32F;
    glGenTextures(1, &t.id_);
    glBindTexture(GL_TEXTURE_2D, t.id_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, rgba);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    t.linear_ = set_filters(GL_TEXTURE_2D, t.format_, Filter::Nearest, MipmapMode::None, Filter::Nearest);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    t.bytes_ = texels(width, height, false) * texel_bytes(t.format_);
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
}

Texture Texture::create_data_2d_array(int width, int height, int layers, const float* rgba) {
    Texture t;
    t.width_ = width;
    t.height_ = height;
    t.layers_ = layers;
    t.kind_ = Kind::Tex2DArray;
    t.format_ = TextureFormat::RGBA32F;
    glGenTextures(1, &t.id_);
    glBindTexture(GL_TEXTURE_2D_ARRAY, t.id_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA32F, width, height, layers, 0, GL_RGBA, GL_FLOAT, rgba);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 0);
    t.linear_ = set_filters(GL_TEXTURE_2D_ARRAY, t.format_, Filter::Nearest, MipmapMode::None, Filter::Nearest);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    t.bytes_ = texels(width, height, false) * std::size_t(std::max(layers, 0)) * texel_bytes(t.format_);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    return t;
}

void Texture::update_2d(int x, int y, int width, int height, const void* data) {
    glBindTexture(GL_TEXTURE_2D, id_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    const FormatInfo fi = info(format_);
    glTexSubImage2D(GL_TEXTURE_2D, 0, x, y, width, height, fi.format, fi.type, data);
    glBindTexture(GL_TEXTURE_2D, 0);
}

void Texture::set_sampler(const SamplerState& s) {
    GLenum target = kind_ == Kind::Cube ? GL_TEXTURE_CUBE_MAP : kind_ == Kind::Tex2DArray ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D;
    glBindTexture(target, id_);
    linear_ = set_filters(target, format_, s.min_filter, s.mipmap, s.mag_filter);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, gl_wrap(s.wrap_s));
    glTexParameteri(target, GL_TEXTURE_WRAP_T, gl_wrap(s.wrap_t));
    if (kind_ == Kind::Cube) glTexParameteri(target, GL_TEXTURE_WRAP_R, gl_wrap(s.wrap_r));
    if (s.max_anisotropy > 1.0f && (gl::has_extension("GL_EXT_texture_filter_anisotropic") ||
                                    gl::has_extension("GL_ARB_texture_filter_anisotropic"))) {
        GLfloat max = 1.0f;
        glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT, &max);
        glTexParameterf(target, GL_TEXTURE_MAX_ANISOTROPY_EXT, std::min(max, s.max_anisotropy));
    }
    glBindTexture(target, 0);
}

Texture::~Texture() {
    if (id_) glDeleteTextures(1, &id_);
}

Renderbuffer::Renderbuffer(int width, int height, RenderbufferFormat format, int samples)
    : samples_(samples), format_(format) {
    glGenRenderbuffers(1, &id_);
    glBindRenderbuffer(GL_RENDERBUFFER, id_);
    GLenum internal = GL_RGBA16F;
    switch (format) {
        case RenderbufferFormat::RGBA16F: internal = GL_RGBA16F; break;
        case RenderbufferFormat::RGBA32F: internal = GL_RGBA32F; break;
        case RenderbufferFormat::RGBA8: internal = GL_RGBA8; break;
        case RenderbufferFormat::Depth24: internal = GL_DEPTH_COMPONENT24; break;
    }
    if (samples > 1) glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, internal, width, height);
    else glRenderbufferStorage(GL_RENDERBUFFER, internal, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
}
Renderbuffer::~Renderbuffer() {
    if (id_) glDeleteRenderbuffers(1, &id_);
}

TimerQuery::TimerQuery() { glGenQueries(1, &id_); }
TimerQuery::~TimerQuery() {
    if (id_) glDeleteQueries(1, &id_);
}
void TimerQuery::begin() { glBeginQuery(GL_TIME_ELAPSED, id_); }
void TimerQuery::end() { glEndQuery(GL_TIME_ELAPSED); }
bool TimerQuery::result_ms(double& ms) const {
    GLint available = 0;
    glGetQueryObjectiv(id_, GL_QUERY_RESULT_AVAILABLE, &available);
    if (!available) return false;
    GLuint64 ns = 0;
    glGetQueryObjectui64v(id_, GL_QUERY_RESULT, &ns);
    ms = double(ns) * 1e-6;
    return true;
}

Framebuffer::Framebuffer() { glGenFramebuffers(1, &id_); }
Framebuffer::~Framebuffer() {
    if (id_) glDeleteFramebuffers(1, &id_);
}
void Framebuffer::attach_color(const Texture& texture) {
    TextureFormat f = texture.format();
    color_normalized_ = f == TextureFormat::RGBA8 || f == TextureFormat::SRGB8_ALPHA8 || f == TextureFormat::R8;
    glBindFramebuffer(GL_FRAMEBUFFER, id_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                           texture.kind() == Texture::Kind::Tex2DMultisample ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D,
                           texture.id(), 0);
}
void Framebuffer::attach_color(const Renderbuffer& rb) {
    color_normalized_ = rb.format() == RenderbufferFormat::RGBA8;
    glBindFramebuffer(GL_FRAMEBUFFER, id_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb.id());
}
void Framebuffer::attach_depth(const Renderbuffer& rb) {
    glBindFramebuffer(GL_FRAMEBUFFER, id_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb.id());
}
void Framebuffer::attach_depth(const Texture& depth) {
    glBindFramebuffer(GL_FRAMEBUFFER, id_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth.id(), 0);
    const GLenum none = GL_NONE;
    glDrawBuffers(1, &none);
    glReadBuffer(GL_NONE);
}
void Framebuffer::check() const {
    glBindFramebuffer(GL_FRAMEBUFFER, id_);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error("GL", "framebuffer", "incomplete framebuffer (status 0x" + [&] {
            char buf[16];
            std::snprintf(buf, sizeof buf, "%X", status);
            return std::string(buf);
        }() + ")");
}

int max_samples() {
    GLint n = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &n);
    return n;
}

namespace {
GLuint compile(const std::string& name, GLenum type, const std::string& source) {
    GLuint s = glCreateShader(type);
    const char* src = source.c_str();
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
        std::string log(std::size_t(std::max(len, 1)), '\0');
        glGetShaderInfoLog(s, len, nullptr, log.data());
        glDeleteShader(s);
        throw Error(name, type == GL_VERTEX_SHADER ? "vertex shader" : "fragment shader", "compile failed:\n" + log);
    }
    return s;
}
}  // namespace

Program::Program(const std::string& name, const std::string& vs, const std::string& fs) {
    GLuint v = compile(name, GL_VERTEX_SHADER, vs);
    GLuint f = 0;
    try {
        f = compile(name, GL_FRAGMENT_SHADER, fs);
    } catch (...) {
        glDeleteShader(v);
        throw;
    }
    id_ = glCreateProgram();
    glAttachShader(id_, v);
    glAttachShader(id_, f);
    // Fixed attribute locations shared by every mesh shader, skinning's (6, 7) after the
    // vertex's own, then instanced draws' per-instance matrices: the model (a mat4 at 8..11) and
    // its normal matrix (a mat3 at 12..14), and the baked occlusion (15): the 16 attributes
    // OpenGL ES 3.0 guarantees (morph targets are read from a texture).
    const char* attributes[] = {"a_position", "a_normal", "a_tangent", "a_uv0", "a_uv1", "a_color", "a_joints", "a_weights"};
    for (unsigned i = 0; i < 8; ++i) glBindAttribLocation(id_, i, attributes[i]);
    glBindAttribLocation(id_, kInstanceModelLocation, "a_instance_model");
    glBindAttribLocation(id_, kInstanceNormalLocation, "a_instance_normal");
    glBindAttribLocation(id_, kOcclusionLocation, "a_occlusion");
    glLinkProgram(id_);
    glDeleteShader(v);
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(id_, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &len);
        std::string log(std::size_t(std::max(len, 1)), '\0');
        glGetProgramInfoLog(id_, len, nullptr, log.data());
        throw Error(name, "program", "link failed:\n" + log);
    }
    // Every active uniform's location, once (block members have none and are skipped).
    GLint count = 0, longest = 0;
    glGetProgramiv(id_, GL_ACTIVE_UNIFORMS, &count);
    glGetProgramiv(id_, GL_ACTIVE_UNIFORM_MAX_LENGTH, &longest);
    std::string buffer(std::size_t(std::max(longest, 1)), '\0');
    for (GLint i = 0; i < count; ++i) {
        GLsizei length = 0;
        GLint size = 0;
        GLenum type = 0;
        glGetActiveUniform(id_, GLuint(i), GLsizei(buffer.size()), &length, &size, &type, buffer.data());
        std::string uniform(buffer.data(), std::size_t(std::max(length, 0)));
        if (uniform.size() > 3 && uniform.compare(uniform.size() - 3, 3, "[0]") == 0) uniform.resize(uniform.size() - 3);
        int loc = glGetUniformLocation(id_, uniform.c_str());
        if (loc >= 0) locations_.emplace(std::move(uniform), loc);
    }
}
Program::~Program() {
    if (id_) glDeleteProgram(id_);
}
void Program::use() const { glUseProgram(id_); }
int Program::location(std::string_view uniform) const {
    auto it = locations_.find(uniform);
    return it != locations_.end() ? it->second : -1;
}
void Program::bind_uniform_block(const char* block, unsigned binding) const {
    GLuint index = glGetUniformBlockIndex(id_, block);
    if (index != GL_INVALID_INDEX) glUniformBlockBinding(id_, index, binding);
}
std::vector<int> Program::uniform_offsets(const std::vector<std::string>& names) const {
    std::vector<int> out(names.size(), -1);
    for (std::size_t i = 0; i < names.size(); ++i) {
        const char* n = names[i].c_str();
        GLuint index = GL_INVALID_INDEX;
        glGetUniformIndices(id_, 1, &n, &index);
        if (index == GL_INVALID_INDEX) continue;
        GLint offset = -1;
        glGetActiveUniformsiv(id_, 1, &index, GL_UNIFORM_OFFSET, &offset);
        out[i] = offset;
    }
    return out;
}
int Program::uniform_block_size(const char* block) const {
    GLuint index = glGetUniformBlockIndex(id_, block);
    if (index == GL_INVALID_INDEX) return 0;
    GLint size = 0;
    glGetActiveUniformBlockiv(id_, index, GL_UNIFORM_BLOCK_DATA_SIZE, &size);
    return size;
}
void Program::set(std::string_view n, int v) const { glUniform1i(location(n), v); }
void Program::set(std::string_view n, float v) const { glUniform1f(location(n), v); }
void Program::set(std::string_view n, glm::vec2 v) const { glUniform2fv(location(n), 1, glm::value_ptr(v)); }
void Program::set(std::string_view n, glm::vec3 v) const { glUniform3fv(location(n), 1, glm::value_ptr(v)); }
void Program::set(std::string_view n, glm::vec4 v) const { glUniform4fv(location(n), 1, glm::value_ptr(v)); }
void Program::set(std::string_view n, const glm::mat3& v) const {
    glUniformMatrix3fv(location(n), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(std::string_view n, const glm::mat4& v) const {
    glUniformMatrix4fv(location(n), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(std::string_view n, std::span<const glm::vec4> v) const {
    if (!v.empty()) glUniform4fv(location(n), GLsizei(v.size()), glm::value_ptr(v[0]));
}
void Program::set(std::string_view n, std::span<const glm::vec3> v) const {
    if (!v.empty()) glUniform3fv(location(n), GLsizei(v.size()), glm::value_ptr(v[0]));
}
void Program::set(std::string_view n, std::span<const glm::mat4> v) const {
    if (!v.empty()) glUniformMatrix4fv(location(n), GLsizei(v.size()), GL_FALSE, glm::value_ptr(v[0]));
}
void Program::set(std::string_view n, std::span<const float> v) const {
    if (!v.empty()) glUniform1fv(location(n), GLsizei(v.size()), v.data());
}

}  // namespace fresnel::gpu
