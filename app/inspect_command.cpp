// `invfree inspect`: one triangle's stress and stress derivative at a step (issue 26).
#include "app/commands.h"

namespace invfree {

void register_inspect_command(CLI::App& /*app*/, int& /*exit_code*/) {}

}  // namespace invfree
