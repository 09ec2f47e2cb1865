#include "fresnel/core/version.h"

namespace fresnel {

std::string_view version() { return FRESNEL_VERSION_STRING; }

}  // namespace fresnel
