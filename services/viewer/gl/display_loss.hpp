#pragma once
// What the viewer does when its X server goes away (Xvfb stopped first, a closed session).
namespace slam::viewer {

// Xlib's default reaction to a lost display is exit() from inside whatever GL or GLFW call noticed
// it: static destructors then run while the DDS threads still publish, which writes through freed
// memory. This handler prints one line and ends the process at once instead (exit status 1).
// Call after glfwInit(); harmless without an X connection.
void end_process_on_display_loss();

}  // namespace slam::viewer
