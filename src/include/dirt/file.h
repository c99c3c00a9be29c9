/* DIRT engine: atomic file output.
 *
 * Every file the engine writes (images, JSON stats, ...) goes through an
 * atomic file: the bytes go to a temporary file `<path>.tmp.HOST.PID.XXXXXX`
 * (the writer's host name and process id; mkstemp(3)) in the same directory
 * as `path`; commit flushes, fsyncs and
 * rename(2)s it over `path`. Readers therefore see either the previous file
 * (or no file) or the complete new one, never a partial write. On any failure
 * and on abort the temporary file is removed and `path` is left untouched.
 *
 *     dirt_atomic_file *f = dirt_atomic_open("out/stats.json");
 *     if (!f) return false;                  // reason already logged
 *     fprintf(dirt_atomic_stream(f), "{...}\n");
 *     if (!dirt_atomic_commit(f)) return false; // f is freed either way
 *
 * A dirt_atomic_file is used by one thread at a time. With
 * dirt_cleanup_on_signals installed, SIGINT, SIGTERM, SIGHUP and SIGQUIT
 * remove every temporary file still open (and the paths added with
 * dirt_cleanup_add) before the process ends as the signal says. */
#ifndef DIRT_FILE_H
#define DIRT_FILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "dirt/api.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dirt_atomic_file dirt_atomic_file;

/* Creates the temporary file for an atomic write of `path`. The new file gets
 * mode 0644, or the permission bits of the file it replaces when `path`
 * already exists. Returns NULL after logging why (directory missing or not
 * writable, path too long, out of memory). */
DIRT_API dirt_atomic_file *dirt_atomic_open(const char *path);

/* Binary stdio stream onto the temporary file, owned by `f`: write (and
 * seek) freely, never fclose it. Errors on it are detected at commit. */
DIRT_API FILE *dirt_atomic_stream(dirt_atomic_file *f);

/* Path of the temporary file (for messages) and the final path. */
DIRT_API const char *dirt_atomic_temp_path(const dirt_atomic_file *f);
DIRT_API const char *dirt_atomic_target_path(const dirt_atomic_file *f);

/* Flushes, fsyncs and renames the temporary file to the target path, then
 * fsyncs the directory (a failure there is only a warning). Frees `f` in
 * every case. On failure (including any earlier error on the stream) logs
 * why, removes the temporary file and returns false; the target path keeps
 * its previous content or absence. */
DIRT_API bool dirt_atomic_commit(dirt_atomic_file *f);

/* Discards the write: closes and removes the temporary file and frees `f`.
 * The target path is untouched. Accepts NULL. */
DIRT_API void dirt_atomic_abort(dirt_atomic_file *f);

/* Files to remove when a signal ends the process: the open temporary files
 * are added and removed by the functions above; a program adds its own (a
 * claim file). dirt_cleanup_add returns a slot (-1 when the list of 32 is
 * full or the path too long: logged); dirt_cleanup_remove forgets it. Main
 * thread only. */
DIRT_API int dirt_cleanup_add(const char *path);
DIRT_API void dirt_cleanup_remove(int slot);
/* Installs the handlers (SIGINT, SIGTERM, SIGHUP, SIGQUIT) that remove
 * those files, then end the process with the signal's default action.
 * False after logging. */
DIRT_API bool dirt_cleanup_on_signals(void);
/* Bracket the making of a file and its dirt_cleanup_add (main thread):
 * the calling thread's signals are blocked, and a handler running on
 * another thread waits until dirt_cleanup_release, so no signal can end
 * the process between the two and leave the file (dirt_atomic_open and
 * the claims of dirt-render do this). */
DIRT_API void dirt_cleanup_hold(void);
DIRT_API void dirt_cleanup_release(void);

/* Convenience: atomically replaces `path` with `size` bytes from `data`.
 * Returns false after logging why; nothing is left behind on failure. */
DIRT_API bool dirt_write_file_atomic(const char *path, const void *data, size_t size);

#ifdef __cplusplus
}
#endif
#endif
