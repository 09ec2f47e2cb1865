#pragma once
// Assembles shader sources from the embedded files in shaders/: resolves
// #include "file", prepends the GLSL version line for the target API and the
// feature #defines, and caches compiled programs by (files, defines).
#include <compare>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "fresnel/gpu/context.h"
#include "fresnel/gpu/resources.h"
#include "details/shader_features.h"

namespace fresnel {

enum class GlslTarget { Gl33, Es30 };
// The GLSL dialect of a context's API: 330 core for OpenGL 3.3, 300 es for OpenGL ES 3.0.
GlslTarget glsl_target(gpu::Api api);

// The source of `file` with includes resolved and `defines` ("NAME" or "NAME VALUE") added:
// the version line (and, for ES, default precisions), one #define line per define, then the
// file with each `#include "name"` line replaced by that file, each file at most once.
// Throws fresnel::Error for a missing file, an include cycle or a malformed #include.
std::string assemble_shader(const std::string& file, const std::vector<std::string>& defines,
                            GlslTarget target = GlslTarget::Gl33);

// Where assemble_shader reads a file's text; an empty view means there is no such file.
using ShaderFiles = std::function<std::string_view(const std::string& name)>;
// The same, reading the files from `files` instead of the embedded shaders/ (tests).
std::string assemble_shader(const std::string& file, const std::vector<std::string>& defines, GlslTarget target,
                            const ShaderFiles& files);

class ShaderLibrary {
public:
    // The dialect is the context's (glsl_target(context.api())): no default, so that a caller on
    // OpenGL ES cannot get desktop GLSL by leaving it out.
    explicit ShaderLibrary(GlslTarget target) : target_(target) {}
    // Returns the program for this vertex/fragment pair and define set, compiling it once.
    const gpu::Program& get(const std::string& vertex, const std::string& fragment, std::vector<std::string> defines);
    // The variant of a mesh shader pair for a feature set (see shader_features.h): its
    // defines are feature_defines(features). Looked up by (vertex, fragment, mask).
    const gpu::Program& get(const std::string& vertex, const std::string& fragment, FeatureMask features);
    // The same with the frame variant compiled in (frame_defines(frame)).
    const gpu::Program& get(const std::string& vertex, const std::string& fragment, FeatureMask features,
                            FrameVariant frame);

    // A program looked up by a caller's key rather than by its defines spelled out, so that a
    // draw builds no strings: `make_defines()` (returning the std::vector<std::string> of
    // defines) runs only the first time a key is seen. `family` tells apart the callers'
    // define schemes (0 is the mesh variants' own: the two get() above); `frame` is a
    // FrameVariant::key() or -1, `extra` whatever else the family's defines depend on.
    struct VariantKey {
        int family = 0;
        FeatureMask features = 0;
        int frame = -1;
        std::uint32_t extra = 0;
        auto operator<=>(const VariantKey&) const = default;
    };
    template <class MakeDefines>
    const gpu::Program& get_keyed(const std::string& vertex, const std::string& fragment, const VariantKey& key,
                                  MakeDefines&& make_defines) {
        auto k = std::make_tuple(vertex, fragment, key);
        auto it = variants_.find(k);
        if (it != variants_.end()) return *it->second;
        const gpu::Program& p = get(vertex, fragment, make_defines());
        variants_.emplace(std::move(k), &p);
        return p;
    }
    std::size_t size() const { return programs_.size(); }
    GlslTarget target() const { return target_; }

    // Development: read the shader files from `folder` (a copy of shaders/) instead of the
    // embedded ones, from the next program compiled on; empty: the embedded files again.
    void set_source_folder(const std::string& folder);
    // Reads the files again and recompiles every cached program from them. All or nothing:
    // when one fails to read, compile or link, every program stays as it was and the error
    // is returned; "" on success (programs got before are then invalid: get them again).
    std::string reload();

    // Connects a program's uniform blocks (FrameBlock, MaterialBlock) to their binding points
    // (uniform_blocks.h); done for every program the library makes.
    static void bind_blocks(const gpu::Program& program);

private:
    std::string source(const std::string& file, const std::vector<std::string>& defines);
    GlslTarget target_;
    std::string folder_;  // set_source_folder
    std::map<std::string, std::string> disk_;  // the files read from folder_ (kept: ShaderFiles returns views)
    struct Sources {
        std::string vertex, fragment;
        std::vector<std::string> defines;
    };
    std::map<std::string, Sources> sources_;  // what each program was built from, for reload()
    std::map<std::string, std::unique_ptr<gpu::Program>> programs_;
    std::map<std::tuple<std::string, std::string, VariantKey>, const gpu::Program*> variants_;  // get_keyed
};

}  // namespace fresnel
