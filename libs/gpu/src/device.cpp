#include "fresnel/gpu/device.h"

#include "gl.h"

namespace fresnel::gpu {

void Device::bind_framebuffer(const Framebuffer* fb) { glBindFramebuffer(GL_FRAMEBUFFER, fb ? fb->id() : 0); }
void Device::viewport(int x, int y, int w, int h) { glViewport(x, y, w, h); }
void Device::scissor(int x, int y, int w, int h) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(x, y, w, h);
}
void Device::no_scissor() { glDisable(GL_SCISSOR_TEST); }
void Device::clear(glm::vec4 c, bool depth) {
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearColor(c.x, c.y, c.z, c.w);
#ifdef __EMSCRIPTEN__
    glClearDepthf(1.0f);
#else
    // glClearDepthf is OpenGL ES (and desktop 4.1 / ARB_ES2_compatibility); 3.3 core has glClearDepth.
    if (gl::is_desktop()) glClearDepth(1.0);
    else glClearDepthf(1.0f);
#endif
    glClear(GL_COLOR_BUFFER_BIT | (depth ? GL_DEPTH_BUFFER_BIT : 0));
}

void Device::apply(const PipelineState& s) {
    if (s.depth_test) glEnable(GL_DEPTH_TEST);
    else glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    // (Seamless cube-map filtering is context state, set once at creation: see Context::init_context.)
    glFrontFace(s.front_ccw ? GL_CCW : GL_CW);
    glDepthMask(s.depth_write ? GL_TRUE : GL_FALSE);
    if (s.cull == Cull::Back) {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
    } else {
        glDisable(GL_CULL_FACE);
    }
    switch (s.blend) {
        case Blend::None: glDisable(GL_BLEND); break;
        case Blend::PremultipliedOver:
            glEnable(GL_BLEND);
            glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
            break;
        case Blend::AlphaOver:
            glEnable(GL_BLEND);
            glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
            break;
    }
    if (s.offset_factor != 0.0f || s.offset_units != 0.0f) {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(s.offset_factor, s.offset_units);
    } else {
        glDisable(GL_POLYGON_OFFSET_FILL);
    }
    if (s.sample_alpha_to_coverage) glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    else glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
}

void Device::bind_texture(int unit, const Texture& t, const SamplerObject* sampler) {
    const std::uint64_t bit = unit >= 0 && unit < 64 ? std::uint64_t(1) << unit : 0;
    if (sampler) {
        glBindSampler(GLuint(unit), sampler->id());
        units_with_sampler_ |= bit;
    } else if (units_with_sampler_ & bit) {
        glBindSampler(GLuint(unit), 0);
        units_with_sampler_ &= ~bit;
    }
    glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    GLenum target = GL_TEXTURE_2D;
    if (t.kind() == Texture::Kind::Cube) target = GL_TEXTURE_CUBE_MAP;
    if (t.kind() == Texture::Kind::Tex2DMultisample) target = GL_TEXTURE_2D_MULTISAMPLE;
    if (t.kind() == Texture::Kind::Tex2DArray) target = GL_TEXTURE_2D_ARRAY;
    glBindTexture(target, t.id());
}

namespace {
GLenum gl_mode(Primitive mode) {
    switch (mode) {
        case Primitive::Points: return GL_POINTS;
        case Primitive::Lines: return GL_LINES;
        case Primitive::LineLoop: return GL_LINE_LOOP;
        case Primitive::LineStrip: return GL_LINE_STRIP;
        case Primitive::Triangles: return GL_TRIANGLES;
    }
    return GL_TRIANGLES;
}
}  // namespace

void Device::draw(const VertexArray& vao, Primitive mode, int count, bool indexed) {
    glBindVertexArray(vao.id());
    if (indexed) glDrawElements(gl_mode(mode), count, GL_UNSIGNED_INT, nullptr);
    else glDrawArrays(gl_mode(mode), 0, count);
    glBindVertexArray(0);
}

void Device::draw_instanced(const VertexArray& vao, Primitive mode, int count, bool indexed, int instances) {
    glBindVertexArray(vao.id());
    if (indexed) glDrawElementsInstanced(gl_mode(mode), count, GL_UNSIGNED_INT, nullptr, instances);
    else glDrawArraysInstanced(gl_mode(mode), 0, count, instances);
    glBindVertexArray(0);
}

VertexArray& Device::empty_vao() {
    if (!empty_vao_) empty_vao_ = std::make_unique<VertexArray>();
    return *empty_vao_;
}

void Device::draw_fullscreen() {
    glBindVertexArray(empty_vao().id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
}

void Device::blit_color(const Framebuffer& src, const Framebuffer& dst, int w, int h) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, src.id());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, dst.id());
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

std::vector<float> Device::read_rgba32f(const Framebuffer& fb, int w, int h) {
    std::vector<float> px(std::size_t(w) * h * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fb.id());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (fb.color_normalized()) {
        // Fixed-point targets: OpenGL ES reads them back only as RGBA / UNSIGNED_BYTE.
        std::vector<unsigned char> bytes(px.size());
        glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
        for (std::size_t i = 0; i < px.size(); ++i) px[i] = float(bytes[i]) / 255.0f;
    } else {
        // Float targets: RGBA / FLOAT (on ES 3.0 allowed for float colour buffers).
        glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, px.data());
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return px;
}

std::vector<std::uint8_t> Device::read_rgba8(const Framebuffer& fb, int w, int h) {
    std::vector<std::uint8_t> px(std::size_t(w) * std::size_t(h) * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fb.id());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return px;
}

std::vector<std::uint8_t> Device::read_default_rgba8(int x, int y, int w, int h) {
    std::vector<std::uint8_t> px(std::size_t(w) * std::size_t(h) * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(x, y, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return px;
}

namespace {
// Counts the names in [1, bound] for which `is` holds, where bound covers every name the
// driver has handed out: past the name a fresh object gets now (drivers hand out increasing
// names, or reuse the lowest free one) and past the last live name found by 4096 names.
template <class Gen, class Is, class Del>
int count_live(Gen gen, Is is, Del del) {
    GLuint fresh = gen();
    del(fresh);
    int live = 0;
    GLuint last_live = 0;
    for (GLuint name = 1; name <= fresh + 64u || name <= last_live + 4096u; ++name) {
        if (name == fresh) continue;
        if (is(name) == GL_TRUE) {
            ++live;
            last_live = name;
        }
    }
    return live;
}
}  // namespace

LiveObjects Device::live_objects() {
    LiveObjects o;
    auto gen_with = [](void (*gen)(GLsizei, GLuint*)) {
        return [gen] {
            GLuint n = 0;
            gen(1, &n);
            return n;
        };
    };
    auto del_with = [](void (*del)(GLsizei, const GLuint*)) { return [del](GLuint n) { del(1, &n); }; };
    o.buffers = count_live(gen_with(glGenBuffers), glIsBuffer, del_with(glDeleteBuffers));
    o.vertex_arrays = count_live(gen_with(glGenVertexArrays), glIsVertexArray, del_with(glDeleteVertexArrays));
    o.textures = count_live(gen_with(glGenTextures), glIsTexture, del_with(glDeleteTextures));
    o.renderbuffers = count_live(gen_with(glGenRenderbuffers), glIsRenderbuffer, del_with(glDeleteRenderbuffers));
    o.framebuffers = count_live(gen_with(glGenFramebuffers), glIsFramebuffer, del_with(glDeleteFramebuffers));
    // Programs and shaders share one namespace.
    auto gen_program = [] { return glCreateProgram(); };
    auto del_program = [](GLuint n) { glDeleteProgram(n); };
    o.programs = count_live(gen_program, glIsProgram, del_program);
    o.shaders = count_live(gen_program, glIsShader, del_program);
    return o;
}

std::string Device::take_errors() {
    std::string out;
    for (int i = 0; i < 16; ++i) {
        GLenum e = glGetError();
        if (e == GL_NO_ERROR) break;
        const char* name = "GL error";
        switch (e) {
            case GL_INVALID_ENUM: name = "GL_INVALID_ENUM"; break;
            case GL_INVALID_VALUE: name = "GL_INVALID_VALUE"; break;
            case GL_INVALID_OPERATION: name = "GL_INVALID_OPERATION"; break;
            case GL_INVALID_FRAMEBUFFER_OPERATION: name = "GL_INVALID_FRAMEBUFFER_OPERATION"; break;
            case GL_OUT_OF_MEMORY: name = "GL_OUT_OF_MEMORY"; break;
        }
        if (!out.empty()) out += ", ";
        out += name;
    }
    return out;
}

void Device::finish() { glFinish(); }

}  // namespace fresnel::gpu
