#pragma once
// The way back from a Job to a command line: the `fresnel render ...` command that renders a
// Job (the viewer's "copy as command line"), and the GL context the job flags ask for.
#include <string>

#include "fresnel/gpu/context.h"
#include "fresnel/job/job.h"
#include "job_options.h"

namespace fresnel::cli {

// The GL context the flags ask for (--gl, --gl-debug; debug builds always debug), logging to
// stderr: the one setup of render, batch's workers and the viewer's window.
gpu::ContextOptions context_options(const RenderOptions& flags);

// Quotes `s` for a POSIX shell when it needs it ('...').
std::string shell_quote(const std::string& s);

// The `fresnel render` command line that renders `job` to `output`: the job's model, then
// only the flags whose values differ from the defaults (numbers in their shortest exact
// form, so the line parses back to the same job; lights as dir:/point: specs).
std::string render_command_line(const Job& job, const std::string& output);

}  // namespace fresnel::cli
