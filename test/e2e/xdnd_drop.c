/* xdnd_drop WINDOW FILE...: drops FILEs on the X window WINDOW (a decimal
 * id, as `xdotool search` prints it) the way a file manager does, through
 * the XDND protocol (version 5): enter, position over the window's centre,
 * drop, then answer the target's request for the text/uri-list selection.
 * Exit status 0 when the target took the drop (its XdndFinished came, or
 * the selection was read when the target does not send one), 1 when it
 * refused or did not answer within 10 s, 2 on bad arguments. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <limits.h>
#include <poll.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

/* Appends "file://PATH\r\n" to `out` (size n), PATH made absolute and
 * percent-encoded. False when it does not fit or cannot be resolved. */
static bool append_uri(char *out, size_t n, const char *path)
{
    char abs[PATH_MAX];
    if (!realpath(path, abs))
        return false;
    size_t len = strlen(out);
    int w = snprintf(out + len, n - len, "file://");
    len += (size_t)w;
    for (const unsigned char *p = (const unsigned char *)abs; *p; p++) {
        bool plain = (*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') ||
                     (*p >= '0' && *p <= '9') || strchr("/-._~", *p);
        w = plain ? snprintf(out + len, n - len, "%c", *p)
                  : snprintf(out + len, n - len, "%%%02X", *p);
        if (w < 0 || (size_t)w >= n - len)
            return false;
        len += (size_t)w;
    }
    w = snprintf(out + len, n - len, "\r\n");
    return w > 0 && (size_t)w < n - len;
}

static void send_msg(Display *d, Window target, Atom type, const long l[5])
{
    XEvent ev;
    memset(&ev, 0, sizeof(ev));
    ev.xclient.type = ClientMessage;
    ev.xclient.display = d;
    ev.xclient.window = target;
    ev.xclient.message_type = type;
    ev.xclient.format = 32;
    for (int i = 0; i < 5; i++)
        ev.xclient.data.l[i] = l[i];
    XSendEvent(d, target, False, NoEventMask, &ev);
    XFlush(d);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: xdnd_drop WINDOW FILE...\n");
        return 2;
    }
    char *end;
    unsigned long target = strtoul(argv[1], &end, 10);
    if (*end || !target) {
        fprintf(stderr, "xdnd_drop: '%s' is not a window id\n", argv[1]);
        return 2;
    }
    static char uris[65536];
    for (int i = 2; i < argc; i++) {
        if (!append_uri(uris, sizeof(uris), argv[i])) {
            fprintf(stderr, "xdnd_drop: cannot name '%s' as a URI\n", argv[i]);
            return 2;
        }
    }
    Display *d = XOpenDisplay(NULL);
    if (!d) {
        fprintf(stderr, "xdnd_drop: no X display\n");
        return 2;
    }
    Atom aware = XInternAtom(d, "XdndAware", False);
    Atom enter = XInternAtom(d, "XdndEnter", False);
    Atom position = XInternAtom(d, "XdndPosition", False);
    Atom status = XInternAtom(d, "XdndStatus", False);
    Atom drop = XInternAtom(d, "XdndDrop", False);
    Atom finished = XInternAtom(d, "XdndFinished", False);
    Atom leave = XInternAtom(d, "XdndLeave", False);
    Atom selection = XInternAtom(d, "XdndSelection", False);
    Atom copy = XInternAtom(d, "XdndActionCopy", False);
    Atom uri_list = XInternAtom(d, "text/uri-list", False);

    /* The target must say it takes drops, and which version. */
    Atom type;
    int format;
    unsigned long count, left;
    unsigned char *prop = NULL;
    if (XGetWindowProperty(d, target, aware, 0, 1, False, AnyPropertyType, &type, &format, &count,
                           &left, &prop) != Success ||
        !prop || count < 1) {
        fprintf(stderr, "xdnd_drop: window %lu is not XdndAware\n", target);
        return 1;
    }
    long version = *(long *)prop < 5 ? *(long *)prop : 5;
    XFree(prop);

    Window root = DefaultRootWindow(d);
    Window source = XCreateSimpleWindow(d, root, 0, 0, 1, 1, 0, 0, 0);
    XSetSelectionOwner(d, selection, source, CurrentTime);
    XWindowAttributes wa;
    XGetWindowAttributes(d, target, &wa);
    int rx, ry;
    Window child;
    XTranslateCoordinates(d, target, root, wa.width / 2, wa.height / 2, &rx, &ry, &child);

    send_msg(d, target, enter, (long[5]){(long)source, version << 24, (long)uri_list, 0, 0});
    send_msg(d, target, position,
             (long[5]){(long)source, 0, ((long)rx << 16) | (ry & 0xffff), CurrentTime, (long)copy});

    int rc = 1;
    bool dropped = false, served = false;
    double deadline = now_s() + 10;
    while (now_s() < deadline) {
        if (!XPending(d)) {
            struct pollfd pf = {.fd = ConnectionNumber(d), .events = POLLIN};
            poll(&pf, 1, 50);
            if (served && version < 2 && !XPending(d)) {
                rc = 0; /* no XdndFinished before version 2: the read is the end */
                break;
            }
            continue;
        }
        XEvent ev;
        XNextEvent(d, &ev);
        if (ev.type == ClientMessage && ev.xclient.message_type == status && !dropped) {
            if (!(ev.xclient.data.l[1] & 1)) {
                fprintf(stderr, "xdnd_drop: the window refused text/uri-list\n");
                send_msg(d, target, leave, (long[5]){(long)source, 0, 0, 0, 0});
                break;
            }
            send_msg(d, target, drop, (long[5]){(long)source, 0, CurrentTime, 0, 0});
            dropped = true;
        } else if (ev.type == SelectionRequest) {
            XSelectionRequestEvent *rq = &ev.xselectionrequest;
            XEvent reply;
            memset(&reply, 0, sizeof(reply));
            reply.xselection.type = SelectionNotify;
            reply.xselection.display = d;
            reply.xselection.requestor = rq->requestor;
            reply.xselection.selection = rq->selection;
            reply.xselection.target = rq->target;
            reply.xselection.time = rq->time;
            reply.xselection.property = None;
            if (rq->target == uri_list) {
                Atom where = rq->property != None ? rq->property : rq->target;
                XChangeProperty(d, rq->requestor, where, uri_list, 8, PropModeReplace,
                                (unsigned char *)uris, (int)strlen(uris));
                reply.xselection.property = where;
                served = true;
            }
            XSendEvent(d, rq->requestor, False, NoEventMask, &reply);
            XFlush(d);
        } else if (ev.type == ClientMessage && ev.xclient.message_type == finished) {
            rc = served ? 0 : 1;
            if (!served)
                fprintf(stderr, "xdnd_drop: finished without reading the files\n");
            break;
        }
    }
    if (rc && now_s() >= deadline)
        fprintf(stderr, "xdnd_drop: no answer from window %lu in 10 s\n", target);
    XDestroyWindow(d, source);
    XCloseDisplay(d);
    return rc;
}
