// The energy landscape of a model over its singular values (issue 26).
#pragma once

namespace invfree {}  // namespace invfree
