/* The session's internals shared by its files (session.c, the engines'
 * engine*.c, pictures.c, agreement.c, stats_json.c, output.c, errors.c) and
 * the tests: the technique objects of the last build, and the error ids of
 * dirt_session_last_error. */
#ifndef DIRT_SESSION_INTERNAL_H
#define DIRT_SESSION_INTERNAL_H

#include <stdbool.h>

#include "dirt/ads.h"
#include "dirt/session.h"
#include "mmrt/mmrt.h"

/* The DIRT structure or MMRT A-buffer of the last build (NULL for other
 * engines or before a build): for pictures, checks and tests. */
dirt_ads *dirt_session_ads(dirt_session *s);
dirt_mmrt *dirt_session_mmrt(dirt_session *s);

/* dirt_session_last_error's bookkeeping: every public call that can fail
 * starts with session_begin() (OK), and each failure calls session_fail
 * with its reason; the first reason of a call stays (a caller's later
 * RENDER does not hide a more precise reason found below it). Returns
 * false, for `return session_fail(...)`. */
void session_begin(void);
bool session_fail(enum dirt_session_error e);

#endif
