/* Internal header of the atomic file writer (src/io/atomic_file.c).
 *
 * The API is public and documented in dirt/file.h; this header exists so
 * code inside src/ can include "io/atomic_file.h" beside the implementation. */
#ifndef DIRT_IO_ATOMIC_FILE_H
#define DIRT_IO_ATOMIC_FILE_H

#include "dirt/file.h"

#endif
