#pragma once
// GPU tests: a headless context, or none with the reason, which the test skips with
// (`auto context = try_headless_context(why); if (!context) GTEST_SKIP() << why;`).
#include <memory>
#include <string>

#include "fresnel/core/error.h"
#include "fresnel/gpu/context.h"

namespace fresnel::test_support {

inline std::unique_ptr<gpu::Context> try_headless_context(std::string& why, const gpu::ContextOptions& options = {}) {
    try {
        return gpu::create_headless_context(options);
    } catch (const Error& e) {
        why = e.what();
        return nullptr;
    }
}

// The same for one API: OpenGL 3.3 core or OpenGL ES 3.0 (the web page's dialect).
inline std::unique_ptr<gpu::Context> try_headless_context(std::string& why, gpu::Api api) {
    gpu::ContextOptions options;
    options.api = api;
    return try_headless_context(why, options);
}

}  // namespace fresnel::test_support
