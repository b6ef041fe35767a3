/* glx_spin.c: a GLX program that clears and swaps until it is stopped -- the stand-in for osgOcean's
 * example in the test of swap_timer.c (tests/CMakeLists.txt, osgocean_swap_timer): like the example it
 * never ends by itself and calls glXSwapBuffers through the dynamic linker. */
#include <GL/gl.h>
#include <GL/glx.h>
#include <stdio.h>

int main(void) {
    Display* dpy = XOpenDisplay(NULL);
    if (!dpy) {
        fprintf(stderr, "glx_spin: no X display\n");
        return 1;
    }
    int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_DEPTH_SIZE, 24, None};
    XVisualInfo* visual = glXChooseVisual(dpy, DefaultScreen(dpy), attributes);
    if (!visual) {
        fprintf(stderr, "glx_spin: no double-buffered RGBA visual\n");
        return 1;
    }
    Window root = RootWindow(dpy, visual->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(dpy, root, visual->visual, AllocNone);
    Window win = XCreateWindow(dpy, root, 0, 0, 320, 180, 0, visual->depth, InputOutput, visual->visual,
                               CWColormap, &wa);
    XMapWindow(dpy, win);
    GLXContext ctx = glXCreateContext(dpy, visual, NULL, True);
    glXMakeCurrent(dpy, win, ctx);
    for (unsigned long frame = 0;; ++frame) {
        glClearColor((float)(frame % 256) / 255.0f, 0.2f, 0.4f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glXSwapBuffers(dpy, win);
    }
}
