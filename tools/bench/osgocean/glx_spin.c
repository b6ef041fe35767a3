/* glx_spin.c: a GLX program that clears and swaps until it is stopped -- the stand-in for osgOcean's
 * example in the tests of swap_timer.c and osgocean_compare.sh (tests/e2e/test_osgocean_compare.py): like
 * the example it never ends by itself and calls glXSwapBuffers through the dynamic linker.
 * Frame k of its 320x180 window: the top-left quarter white, the rest the colour (k mod 256, 51, 102)/255.
 * GLX_SPIN_DRAW=flat draws only the colour (a frame with no "sky"), GLX_SPIN_DRAW=black only black: what
 * the comparison's look at the example's frame must refuse. */
#include <GL/gl.h>
#include <GL/glx.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
    const char* draw = getenv("GLX_SPIN_DRAW");
    int flat = draw && strcmp(draw, "flat") == 0, black = draw && strcmp(draw, "black") == 0;
    for (unsigned long frame = 0;; ++frame) {
        glDisable(GL_SCISSOR_TEST);
        if (black)
            glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        else
            glClearColor((float)(frame % 256) / 255.0f, 0.2f, 0.4f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        if (!flat && !black) {
            glEnable(GL_SCISSOR_TEST);
            glScissor(0, 90, 160, 90); /* GL's window origin is bottom-left: this is the top-left quarter */
            glClearColor(1.0f, 1.0f, 1.0f, 1.0f);
            glClear(GL_COLOR_BUFFER_BIT);
        }
        glXSwapBuffers(dpy, win);
    }
}
