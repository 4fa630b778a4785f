// Writing an output file so that a failure never leaves a half-written file: the
// content goes to "<path>.tmp", which replaces `path` only once it is complete.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace ilp {

// Calls `write` on a stream to "<path>.tmp", flushes and checks it, then renames
// the temporary over `path`. Throws IlpError "<path>: cannot write" (the temporary
// cannot be created) or "<path>: write failed" (the stream failed or the rename did
// not happen). On any exception, including one from `write`, the temporary is
// removed, a previous file at `path` is left as it was, and the exception goes on.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace ilp
