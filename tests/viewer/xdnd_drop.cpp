// xdnd_drop WINDOW X Y FILE: drops FILE on the X window WINDOW (decimal id, e.g. from
// `xdotool search`) at window coordinates X Y through the XDND protocol (version 5), as a file
// manager does, so a test can drop a file on a window under Xvfb. Exit 0 once the target said
// XdndFinished, 1 on a refusal or after 10 s without an answer.
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <sys/select.h>
#include <sys/time.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

static double now(void) {
    struct timeval tv;
    gettimeofday(&tv, NULL);
    return (double)tv.tv_sec + 1e-6 * (double)tv.tv_usec;
}

static void sendMessage(Display* d, Window target, Atom type, long l0, long l1, long l2, long l3, long l4) {
    XEvent e;
    memset(&e, 0, sizeof e);
    e.xclient.type = ClientMessage;
    e.xclient.display = d;
    e.xclient.window = target;
    e.xclient.message_type = type;
    e.xclient.format = 32;
    e.xclient.data.l[0] = l0, e.xclient.data.l[1] = l1, e.xclient.data.l[2] = l2;
    e.xclient.data.l[3] = l3, e.xclient.data.l[4] = l4;
    XSendEvent(d, target, False, NoEventMask, &e);
    XFlush(d);
}

int main(int argc, char** argv) {
    if (argc != 5) {
        fprintf(stderr, "usage: xdnd_drop WINDOW X Y FILE\n");
        return 2;
    }
    Display* d = XOpenDisplay(NULL);
    if (!d) {
        fprintf(stderr, "xdnd_drop: no display\n");
        return 1;
    }
    Window target = (Window)strtoul(argv[1], NULL, 0);
    int wx = atoi(argv[2]), wy = atoi(argv[3]);
    char uri[4200];
    std::snprintf(uri, sizeof uri, "file://%s\r\n", argv[4]);
    Atom enter = XInternAtom(d, "XdndEnter", False);
    Atom position = XInternAtom(d, "XdndPosition", False), status = XInternAtom(d, "XdndStatus", False);
    Atom drop = XInternAtom(d, "XdndDrop", False), finished = XInternAtom(d, "XdndFinished", False);
    Atom selection = XInternAtom(d, "XdndSelection", False), copy = XInternAtom(d, "XdndActionCopy", False);
    Atom uriList = XInternAtom(d, "text/uri-list", False);
    Window source = XCreateSimpleWindow(d, DefaultRootWindow(d), 0, 0, 1, 1, 0, 0, 0);
    XSetSelectionOwner(d, selection, source, CurrentTime);
    int rx = 0, ry = 0;
    Window child;
    XTranslateCoordinates(d, target, DefaultRootWindow(d), wx, wy, &rx, &ry, &child);
    sendMessage(d, target, enter, (long)source, 5L << 24, (long)uriList, 0, 0);
    sendMessage(d, target, position, (long)source, 0, ((long)rx << 16) | ry, CurrentTime, (long)copy);
    int dropped = 0;
    double start = now();
    while (now() - start < 10) {
        if (!XPending(d)) {
            timeval tv = {0, 10000};
            select(0, NULL, NULL, NULL, &tv);
            continue;
        }
        XEvent e;
        XNextEvent(d, &e);
        if (e.type == ClientMessage && e.xclient.message_type == status) {
            if (!(e.xclient.data.l[1] & 1)) {
                fprintf(stderr, "xdnd_drop: the window refuses the drop\n");
                return 1;
            }
            if (!dropped) sendMessage(d, target, drop, (long)source, 0, CurrentTime, 0, 0), dropped = 1;
        } else if (e.type == SelectionRequest) {
            XSelectionRequestEvent* r = &e.xselectionrequest;
            XEvent reply;
            memset(&reply, 0, sizeof reply);
            reply.xselection.type = SelectionNotify;
            reply.xselection.display = d;
            reply.xselection.requestor = r->requestor;
            reply.xselection.selection = r->selection;
            reply.xselection.target = r->target;
            reply.xselection.time = r->time;
            reply.xselection.property = None;
            if (r->target == uriList) {
                XChangeProperty(d, r->requestor, r->property, uriList, 8, PropModeReplace, (unsigned char*)uri,
                                (int)strlen(uri));
                reply.xselection.property = r->property;
            }
            XSendEvent(d, r->requestor, False, NoEventMask, &reply);
            XFlush(d);
        } else if (e.type == ClientMessage && e.xclient.message_type == finished) {
            return 0;
        }
    }
    fprintf(stderr, "xdnd_drop: no answer from window %lu\n", (unsigned long)target);
    return 1;
}
