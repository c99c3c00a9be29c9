/* The session's image written to a file (dirt_session_write_image).
 * Contracts in dirt/session.h. */
#include "dirt/log.h"
#include "dirt/session.h"
#include "session/session_internal.h"

bool dirt_session_write_image(dirt_session *s, const char *path,
                              const dirt_image_write_options *opts)
{
    if (!path) {
        session_begin();
        DIRT_ERROR("writing the session's image: no path");
        return session_fail(DIRT_SESSION_ERR_ARGUMENT);
    }
    const dirt_image *img = dirt_session_image(s); /* begins the call's error record */
    if (!img)
        return false;
    return dirt_image_write(img, path, opts) || session_fail(DIRT_SESSION_ERR_IO);
}
