/* Internal header of the bounded image readers (exr.c, hdr.c), dispatched
 * by dirt_image_read (image.c). `o` is never NULL and has its defaults
 * filled in; `err` is never NULL. Contracts in dirt/image.h. */
#ifndef DIRT_IO_READ_H
#define DIRT_IO_READ_H

#include "dirt/image.h"

dirt_image *io_read_exr(const char *path, const dirt_image_read_opts *o, enum dirt_input_error *err);
dirt_image *io_read_hdr(const char *path, const dirt_image_read_opts *o, enum dirt_input_error *err);

/* The options with their defaults (NULL: all defaults). */
dirt_image_read_opts io_read_defaults(const dirt_image_read_opts *opts);

#endif
