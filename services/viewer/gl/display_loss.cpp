// The Xlib I/O error handler (see display_loss.hpp). Kept apart because <X11/Xlib.h> defines
// macros (Status, None, Bool) that clash with the rest of the code.
#include "viewer/gl/display_loss.hpp"

#include <X11/Xlib.h>
#include <unistd.h>

#include <cstdlib>

namespace slam::viewer {
namespace {

int on_display_lost(Display*) {
  // Only async-signal-safe calls: the process may be in any state here.
  static constexpr char kMessage[] = "slam-viewer: lost the connection to the X display; exiting\n";
  [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
  std::_Exit(1);
}

}  // namespace

void end_process_on_display_loss() {
  XSetIOErrorHandler(on_display_lost);
}

}  // namespace slam::viewer
