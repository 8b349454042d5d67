// Which build of nerv this is: the project version and `git describe` of the source
// tree it was built from ("0.1.0 (7ac1152)", "-dirty" with uncommitted changes).
// Every service reports it in NERV_HEALTH and prints it with --version, so a log says
// which build produced it and `nerv status` shows mixed builds on one bus.
#pragma once

namespace nerv {

const char* buildVersion();

}  // namespace nerv
