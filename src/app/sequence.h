/* Frame sequences for the programs: frame lists, output names, shares of a
 * job array, and the files that let many workers share one output
 * directory (complete frames, claims, stale temporary files). */
#ifndef DIRT_APP_SEQUENCE_H
#define DIRT_APP_SEQUENCE_H

#include <stdbool.h>
#include <stddef.h>

/* Frame numbers in render order (ascending, no duplicates). */
typedef struct seq_frames {
    long *frames;
    size_t count;
} seq_frames;

/* Parses "A:B[:step]" (A..B inclusive) or a list "1,5,10-20" (ranges
 * inclusive; items in any order, duplicates merged). Frames lie in
 * [0, 10^7]; at most 10^6 of them. False with the reason in `why`. */
bool seq_frames_parse(const char *text, seq_frames *out, char *why, size_t size);
void seq_frames_free(seq_frames *f);

/* Keeps the share `k` (1-based) of `n` contiguous shares of the frames
 * (sizes differ by at most one; a share may be empty when n > count). */
bool seq_frames_chunk(seq_frames *f, long k, long n, char *why, size_t size);

/* The share from Slurm's SLURM_ARRAY_TASK_ID, _MIN and _COUNT: false with
 * the reason when they are not set or inconsistent. */
bool seq_slurm_share(long *k, long *n, char *why, size_t size);

/* The widest frame field: frames have at most 8 digits. */
#define SEQ_MAX_FIELD_WIDTH 32

/* Output names. A pattern holds one frame field: a run of '#' (the frame
 * number zero-padded to the run's length, as Blender writes it) or one
 * printf integer conversion (%d, %04d; "%%" is a literal '%'). 1 when
 * `pattern` has one field, 0 when none, -1 when it is malformed (a second
 * field, a stray '%', a field wider than SEQ_MAX_FIELD_WIDTH). */
int seq_pattern_fields(const char *pattern);
/* The file of `frame` (the pattern itself when it has no field). */
void seq_frame_path(const char *pattern, long frame, char *buf, size_t size);

/* Creates the directory that holds `path`, and its parents (mode 0777 less
 * the umask). False with the reason when one cannot be made. The
 * directories made are remembered for seq_remove_made_dirs. */
bool seq_make_parent_dirs(const char *path, char *why, size_t size);
/* A failed run: removes the directories seq_make_parent_dirs made, newest
 * first, each only when empty (a frame completed in one keeps it). */
void seq_remove_made_dirs(void);
/* A run that succeeded: forgets them. */
void seq_forget_made_dirs(void);

/* True when every one of `paths` exists as a regular, non-empty file (an
 * atomic writer renames a complete file into place; temp files never
 * count). */
bool seq_complete(const char *const *paths, int count);

/* Claims for workers sharing a directory: frame file F is claimed by the
 * newest of F.claim.0, F.claim.1, ..., each made with O_EXCL (only one
 * worker can make a given one), holding "HOST PID" of its worker. A claim
 * is stale (its worker died) when its HOST is this host and no process PID
 * exists, at once; any claim whose time stamp is older than `timeout_s`
 * (the only sign for a worker of another host). A stale claim is taken
 * over by making the next generation. A worker keeps its claim fresh with
 * seq_claim_touch. */
typedef struct seq_claim {
    char path[4200];
    bool held;
} seq_claim;

/* Tries to claim `frame_file`. True when this worker now holds it (`c`
 * filled); false when another worker holds a fresh claim or the frame was
 * finished meanwhile (not an error), or on an I/O error (`why` set). */
bool seq_claim_take(const char *frame_file, double timeout_s, seq_claim *c, char *why,
                    size_t size);
/* Refreshes the claim's time stamp (at most once a second; cheap). */
void seq_claim_touch(seq_claim *c);
/* Removes every claim generation of the frame (after it is complete) or
 * only this worker's (when it gives the frame up). */
void seq_claim_release(seq_claim *c, const char *frame_file, bool frame_done);

/* Removes the temporary files an atomic writer left in the directory of
 * `frame`'s file for any file the output `pattern` makes
 * (F.tmp.HOST.PID.XXXXXX) whose writer is gone: on this host when the
 * process no longer exists, from elsewhere when older than `timeout_s`.
 * One directory scan; returns how many were removed. */
int seq_clean_stale_temps(const char *pattern, long frame, double timeout_s);

#endif
