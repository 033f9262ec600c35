// `invfree landscape`: the energy landscape Psi(sigma1, sigma2) of a model (issue 26).
#include "app/commands.h"

namespace invfree {

void register_landscape_command(CLI::App& /*app*/, int& /*exit_code*/) {}

}  // namespace invfree
