/* What made an image or a stats file: the program's command line, the
 * scene, the engine, the seed, the samples, the scene time, the device and
 * the library's version and commit, as text attributes. Every EXR the
 * programs write carries them in its header ("dirt.scene", ...), every
 * stats file in its "provenance" object (the same names without "dirt."). */
#ifndef DIRT_APP_PROVENANCE_H
#define DIRT_APP_PROVENANCE_H

#include <stdbool.h>
#include <stddef.h>

#include "dirt/image.h"
#include "dirt/session.h"

#define APP_PROVENANCE_MAX 12

typedef struct app_provenance {
    char scene[4096];           /* as the user named it ("default" for the embedded one) */
    char command_line[8192];    /* the program's arguments, quoted for a shell */
    char extra_name[32], extra[4096]; /* one more attribute (app_provenance_extra) */
    /* the attributes of the last app_provenance_attrs call */
    char values[8][256];
    dirt_image_attr attrs[APP_PROVENANCE_MAX];
} app_provenance;

/* Records the command line and the scene (NULL: the default scene). */
void app_provenance_init(app_provenance *p, int argc, char **argv, const char *scene);
/* One more attribute for every later call (the viewer's dirt-render
 * options); `name` without the prefix. */
void app_provenance_extra(app_provenance *p, const char *name, const char *value);
/* The attributes of an image or a run described by `st` (engine, seed,
 * samples, time, device): EXR names ("dirt.scene") with `exr`, else the
 * stats file's keys ("scene"). Valid until the next call on `p`; *count
 * gets their number. */
const dirt_image_attr *app_provenance_attrs(app_provenance *p, const dirt_session_stats *st,
                                            bool exr, size_t *count);

/* Appends `arg` to `buf` (of `size`, holding `len` bytes) after a space,
 * quoted for a POSIX shell when it needs it. Returns the new length. */
size_t app_shell_quote(char *buf, size_t size, size_t len, const char *arg);

#endif
