#include "details/shader_library.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "fresnel/core/error.h"
#include "details/uniform_blocks.h"
#include "fresnel/shaders/shaders.h"

namespace fresnel {
namespace {

void expand(const std::string& file, const ShaderFiles& files, std::set<std::string>& included,
            std::vector<std::string>& stack, std::string& out) {
    if (std::find(stack.begin(), stack.end(), file) != stack.end())
        throw Error(file, "#include", "include cycle");
    if (included.count(file)) return;  // each file once (include guards for free)
    std::string_view src = files(file);
    if (src.empty()) throw Error(file, "", "no such embedded shader file");
    included.insert(file);
    stack.push_back(file);
    std::istringstream in{std::string(src)};
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        auto first = line.find_first_not_of(" \t");
        if (first != std::string::npos && line.compare(first, 8, "#include") == 0) {
            auto a = line.find('"'), b = line.rfind('"');
            if (a == std::string::npos || b <= a) throw Error(file, "line " + std::to_string(number), "malformed #include");
            expand(line.substr(a + 1, b - a - 1), files, included, stack, out);
            continue;
        }
        out += line;
        out += '\n';
    }
    stack.pop_back();
}

}  // namespace

GlslTarget glsl_target(gpu::Api api) { return api == gpu::Api::OpenGLES30 ? GlslTarget::Es30 : GlslTarget::Gl33; }

std::string assemble_shader(const std::string& file, const std::vector<std::string>& defines, GlslTarget target) {
    return assemble_shader(file, defines, target, [](const std::string& name) { return shaders::find(name); });
}

std::string assemble_shader(const std::string& file, const std::vector<std::string>& defines, GlslTarget target,
                            const ShaderFiles& files) {
    std::string out = target == GlslTarget::Gl33 ? "#version 330 core\n"
                                                 : "#version 300 es\n"
                                                   "precision highp float;\nprecision highp int;\n"
                                                   "precision highp sampler2D;\nprecision highp samplerCube;\n"
                                                   "precision highp sampler2DShadow;\nprecision highp sampler2DArray;\n";
    for (const auto& d : defines) out += "#define " + d + "\n";
    std::set<std::string> included;
    std::vector<std::string> stack;
    expand(file, files, included, stack, out);
    return out;
}

void ShaderLibrary::bind_blocks(const gpu::Program& program) {
    program.bind_uniform_block("FrameBlock", kFrameBlockBinding);
    program.bind_uniform_block("MaterialBlock", kMaterialBlockBinding);
}

const gpu::Program& ShaderLibrary::get(const std::string& vertex, const std::string& fragment,
                                       std::vector<std::string> defines) {
    std::sort(defines.begin(), defines.end());
    std::string key = vertex + "|" + fragment;
    for (const auto& d : defines) key += "|" + d;
    auto it = programs_.find(key);
    if (it != programs_.end()) return *it->second;
    auto program = std::make_unique<gpu::Program>(key, source(vertex, defines), source(fragment, defines));
    bind_blocks(*program);
    sources_[key] = Sources{vertex, fragment, defines};
    return *programs_.emplace(key, std::move(program)).first->second;
}

std::string ShaderLibrary::source(const std::string& file, const std::vector<std::string>& defines) {
    if (folder_.empty()) return assemble_shader(file, defines, target_);
    return assemble_shader(file, defines, target_, [this](const std::string& name) -> std::string_view {
        auto it = disk_.find(name);
        if (it == disk_.end()) {
            std::ifstream in(std::filesystem::path(folder_) / name, std::ios::binary);
            std::string text;
            if (in) text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
            it = disk_.emplace(name, std::move(text)).first;
        }
        return it->second;
    });
}

void ShaderLibrary::set_source_folder(const std::string& folder) {
    folder_ = folder;
    disk_.clear();
}

std::string ShaderLibrary::reload() {
    disk_.clear();
    std::map<std::string, std::unique_ptr<gpu::Program>> fresh;
    try {
        for (const auto& [key, s] : sources_)
            bind_blocks(*fresh.emplace(key, std::make_unique<gpu::Program>(key, source(s.vertex, s.defines),
                                                                            source(s.fragment, s.defines)))
                             .first->second);
    } catch (const std::exception& e) {
        return e.what();  // `fresh` goes; the programs in use stay
    }
    programs_ = std::move(fresh);
    variants_.clear();  // they pointed into the old programs
    return "";
}

}  // namespace fresnel

namespace fresnel {
const gpu::Program& ShaderLibrary::get(const std::string& vertex, const std::string& fragment, FeatureMask features) {
    return get_keyed(vertex, fragment, {0, features, -1, 0}, [&] { return feature_defines(features); });
}
const gpu::Program& ShaderLibrary::get(const std::string& vertex, const std::string& fragment, FeatureMask features,
                                       FrameVariant frame) {
    return get_keyed(vertex, fragment, {0, features, frame.key(), 0}, [&] {
        std::vector<std::string> defines = feature_defines(features);
        for (auto& d : frame_defines(frame)) defines.push_back(std::move(d));
        return defines;
    });
}
}  // namespace fresnel
