// libFuzzer target: scene files (*.fresnel.json) on arbitrary bytes, read onto a job as
// `fresnel render` reads them (size and nesting limits, every key checked). Relative paths
// resolve under a folder that does not exist, so no file is ever found.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fresnel/job/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fresnel::Diagnostics diag;
    try {
        std::string_view text(reinterpret_cast<const char*>(data), size);
        (void)fresnel::parse_scene_text(text, "fuzz.fresnel.json", "/nonexistent-fresnel-fuzz", fresnel::Job{}, diag);
    } catch (const fresnel::Error&) {
    }
    return 0;
}
