// x11_close_window — asks an X11 window to close the way a window manager's close button does: a ClientMessage
// WM_PROTOCOLS / WM_DELETE_WINDOW (ICCCM §4.2.8.1). xdotool 3.2016 has only windowclose (XDestroyWindow, which a
// GLFW client sees as a BadWindow error, not a close) and windowkill; Xvfb has no window manager.
//
// usage: x11_close_window WINDOW_ID (decimal, as xdotool search prints it). Exit 0 when sent, 1 otherwise.
#include <X11/Xlib.h>

#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: x11_close_window WINDOW_ID\n");
    return 1;
  }
  Display* display = XOpenDisplay(nullptr);
  if (display == nullptr) {
    std::fprintf(stderr, "x11_close_window: cannot open display\n");
    return 1;
  }
  const Window window = std::strtoul(argv[1], nullptr, 0);
  XEvent event{};
  event.xclient.type = ClientMessage;
  event.xclient.window = window;
  event.xclient.message_type = XInternAtom(display, "WM_PROTOCOLS", False);
  event.xclient.format = 32;
  event.xclient.data.l[0] = static_cast<long>(XInternAtom(display, "WM_DELETE_WINDOW", False));
  event.xclient.data.l[1] = CurrentTime;
  const Status sent = XSendEvent(display, window, False, NoEventMask, &event);
  XSync(display, False);
  XCloseDisplay(display);
  return sent != 0 ? 0 : 1;
}
