/* Test-only shim for the ASan build (test/meson.build preloads it): dlclose
 * does nothing, so that the libraries Mesa loads at run time (the llvmpipe
 * driver) stay mapped until the leak check at exit. Unmapped, their global
 * state (reachable until then) shows up as leaks "from <unknown module>"
 * that no suppression can name; mapped, it is reachable and the check sees
 * only real leaks (and test/lsan.supp names Mesa's own by module). */
#include <dlfcn.h>

int dlclose(void *handle)
{
    (void)handle;
    return 0;
}
