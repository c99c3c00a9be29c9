#include <stddef.h>

#include "session/session_internal.h"

static _Thread_local enum dirt_session_error last_error = DIRT_SESSION_ERR_OK;

void session_begin(void)
{
    last_error = DIRT_SESSION_ERR_OK;
}

bool session_fail(enum dirt_session_error e)
{
    if (last_error == DIRT_SESSION_ERR_OK)
        last_error = e;
    return false;
}

enum dirt_session_error dirt_session_last_error(void)
{
    return last_error;
}

const char *dirt_session_error_str(enum dirt_session_error e)
{
    static const char *const msg[] = {
#define DIRT_SESSION_ERR_MSG_(id, text) text,
        DIRT_SESSION_ERRORS(DIRT_SESSION_ERR_MSG_)
#undef DIRT_SESSION_ERR_MSG_
    };
    return (int)e >= 0 && e < DIRT_SESSION_NUM_ERRORS ? msg[e] : "?";
}

const char *dirt_session_error_name(enum dirt_session_error e)
{
    static const char *const name[] = {
#define DIRT_SESSION_ERR_NAME_(id, text) #id,
        DIRT_SESSION_ERRORS(DIRT_SESSION_ERR_NAME_)
#undef DIRT_SESSION_ERR_NAME_
    };
    return (int)e >= 0 && e < DIRT_SESSION_NUM_ERRORS ? name[e] : "?";
}
