/* DIRT engine: the fuzz targets of what users bring (issue 23), beside the
 * scene target of fuzz_scene.h: the image decoders (a glTF texture through
 * the scene loader, dirt_image_read of .exr and .hdr), the environment
 * loader (dirt_env_load) and loading from files (a small tree of files,
 * folders, symbolic links and FIFOs written from the input, then
 * dirt_scene_load of its first file, confined and not). Each entry returns
 * false when an invariant breaks (the driver aborts on it) and leaves the
 * outcome in dirt_fuzz_outcome; the corpus writers make their seeds here
 * (nothing copied). doc/fuzzing.md. */
#ifndef DIRT_FUZZ_INPUTS_H
#define DIRT_FUZZ_INPUTS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* The last entry's outcome: 1 what it loaded loaded, 0 it was refused. */
extern int dirt_fuzz_outcome;

/* data[0] picks the path: 0 the rest as the one texture of a .glb (from
 * memory, budget 64 MiB), 1 as an .exr file, 2 as an .hdr file (both
 * dirt_image_read, limit 64 MiB). A decoded image is read whole. */
bool dirt_fuzz_image_one(const uint8_t *data, size_t size);
/* data[0] & 1 picks .exr or .hdr: the rest written to such a file and
 * loaded by dirt_env_load (budget 64 MiB); a map is evaluated and sampled.
 * A failure's reason must start with an id of dirt/input.h. */
bool dirt_fuzz_env_one(const uint8_t *data, size_t size);
/* The input is a list of records, each [kind][name length][name][content
 * length, 2 bytes little-endian][content]: kind & 3 is 0 a regular file, 1
 * a directory, 2 a symbolic link (to the content), 3 a FIFO; names (only
 * letters, digits, '.', '_', '-', '/') are relative to the scene's folder
 * R/s of a fresh tree R (R/o beside it is "outside"; a name leading out of
 * R is skipped). The first regular file is loaded (budget 64 MiB), confined
 * and then with allow_outside. Invariants: a failed load has an id, and a
 * confined load read no file outside R/s. */
bool dirt_fuzz_files_one(const uint8_t *data, size_t size);

int dirt_fuzz_write_image_corpus(const char *dir);
int dirt_fuzz_write_env_corpus(const char *dir);
int dirt_fuzz_write_files_corpus(const char *dir);

#endif
