// Shader assembly (fresnel/render/shader_library.h): the version line per target, the
// defines, #include expansion (each file once), and the errors for a missing file, an
// include cycle and a malformed #include. Pure CPU: the GL compile is not needed here
// (tests/gpu compiles every program on llvmpipe).
#include "details/shader_library.h"

#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "fresnel/core/error.h"
#include "fresnel/shaders/shaders.h"

using namespace fresnel;

namespace {

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}

// Files for the overload that reads from a map instead of the embedded shaders.
ShaderFiles from(const std::map<std::string, std::string>& files) {
    return [files](const std::string& name) -> std::string_view {
        auto it = files.find(name);
        return it == files.end() ? std::string_view() : std::string_view(it->second);
    };
}

TEST(AssembleShader, VersionLinePerTarget) {
    std::string gl = assemble_shader("pbr.frag", {}, GlslTarget::Gl33);
    EXPECT_EQ(gl.rfind("#version 330 core\n", 0), 0u) << gl.substr(0, 80);
    std::string es = assemble_shader("pbr.frag", {}, GlslTarget::Es30);
    EXPECT_EQ(es.rfind("#version 300 es\nprecision highp float;\nprecision highp int;\n", 0), 0u) << es.substr(0, 80);
    // Exactly one version line, the first.
    EXPECT_EQ(count(gl, "#version"), 1u);
    EXPECT_EQ(count(es, "#version"), 1u);
    EXPECT_EQ(assemble_shader("pbr.vert", {}).rfind("#version 330 core\n", 0), 0u) << "Gl33 is the default";
}

TEST(AssembleShader, DefinesFollowTheVersionInOrder) {
    std::string s = assemble_shader("pbr.frag", {"HAS_NORMAL", "MAX_LIGHTS 4", "USE_IBL"}, GlslTarget::Es30);
    auto l = lines(s);
    ASSERT_GE(l.size(), 10u);
    EXPECT_EQ(l[0], "#version 300 es");
    // The ES preamble: default precisions, samplers included (both dialects then agree).
    EXPECT_EQ(l[1], "precision highp float;");
    EXPECT_EQ(l[4], "precision highp samplerCube;");
    EXPECT_EQ(l[5], "precision highp sampler2DShadow;");  // the shadow atlas (shadows.glsl)
    EXPECT_EQ(l[6], "precision highp sampler2DArray;");   // morph targets (pbr.vert): no default in ES
    EXPECT_EQ(l[7], "#define HAS_NORMAL");
    EXPECT_EQ(l[8], "#define MAX_LIGHTS 4");
    EXPECT_EQ(l[9], "#define USE_IBL");
    // lights.glsl's own default (#ifndef MAX_LIGHTS) comes after, so the define wins.
    EXPECT_LT(s.find("#define MAX_LIGHTS 4"), s.find("#ifndef MAX_LIGHTS"));
}

TEST(AssembleShader, EmbeddedIncludesAreExpandedOnceEach) {
    std::string frag = assemble_shader("pbr.frag", {});
    EXPECT_EQ(frag.find("#include"), std::string::npos) << "an #include line is left";
    // pbr.frag includes these; each embedded file's text appears once.
    for (const char* name : {"common.glsl", "color.glsl", "tonemap.glsl", "brdf.glsl", "lights.glsl", "ibl.glsl",
                             "material_inputs.glsl", "debug.glsl"}) {
        std::string_view src = shaders::find(name);
        ASSERT_FALSE(src.empty()) << name;
        // The file's first line that is not an #include, as a marker of its text.
        std::string marker;
        for (const auto& l : lines(std::string(src)))
            if (l.size() > 10 && l.find("#include") == std::string::npos) {
                marker = l;
                break;
            }
        ASSERT_FALSE(marker.empty()) << name;
        EXPECT_EQ(count(frag, marker + "\n"), 1u) << name << ": '" << marker << "'";
    }
    // Every embedded program assembles.
    for (std::string_view name : shaders::names()) {
        std::string n(name);
        if (n.ends_with(".vert") || n.ends_with(".frag")) {
            EXPECT_NO_THROW(assemble_shader(n, {})) << n;
        }
    }
}

TEST(AssembleShader, DiamondIncludesEachFileOnce) {
    auto files = from({{"main.frag", "top\n#include \"a.glsl\"\n  #include \"b.glsl\"\nbottom\n"},
                       {"a.glsl", "A\n#include \"common.glsl\"\n"},
                       {"b.glsl", "B\n\t#include \"common.glsl\"\n#include \"a.glsl\"\n"},
                       {"common.glsl", "C"}});  // no newline at the end
    std::string s = assemble_shader("main.frag", {"X 1"}, GlslTarget::Gl33, files);
    EXPECT_EQ(s, "#version 330 core\n#define X 1\ntop\nA\nC\nB\nbottom\n");
}

TEST(AssembleShader, MissingFileIsAnError) {
    try {
        assemble_shader("no_such.frag", {});
        ADD_FAILURE() << "no error for a missing file";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "no_such.frag");
        EXPECT_NE(e.reason().find("no such embedded shader file"), std::string::npos) << e.what();
    }
    // ... also when it is an include.
    try {
        assemble_shader("main.frag", {}, GlslTarget::Gl33, from({{"main.frag", "x\n#include \"gone.glsl\"\n"}}));
        ADD_FAILURE() << "no error for a missing include";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "gone.glsl");
        EXPECT_NE(e.reason().find("no such"), std::string::npos) << e.what();
    }
}

TEST(AssembleShader, IncludeCycleIsAnError) {
    auto cycle = from({{"main.frag", "#include \"a.glsl\"\n"},
                       {"a.glsl", "#include \"b.glsl\"\n"},
                       {"b.glsl", "#include \"a.glsl\"\n"}});
    try {
        assemble_shader("main.frag", {}, GlslTarget::Gl33, cycle);
        ADD_FAILURE() << "no error for a -> b -> a";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "a.glsl");
        EXPECT_NE(e.reason().find("include cycle"), std::string::npos) << e.what();
    }
    auto self = from({{"self.glsl", "line\n#include \"self.glsl\"\n"}});
    EXPECT_THROW(assemble_shader("self.glsl", {}, GlslTarget::Gl33, self), Error);
}

TEST(AssembleShader, MalformedIncludeNamesTheLine) {
    for (const char* bad : {"#include common.glsl", "#include \"common.glsl", "#include <common.glsl>", "#include"}) {
        auto files = from({{"main.frag", std::string("one\ntwo\n") + bad + "\n"}, {"common.glsl", "C\n"}});
        try {
            assemble_shader("main.frag", {}, GlslTarget::Gl33, files);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), "main.frag") << bad;
            EXPECT_EQ(e.where(), "line 3") << bad;
            EXPECT_NE(e.reason().find("malformed #include"), std::string::npos) << e.what();
        }
    }
}

}  // namespace
