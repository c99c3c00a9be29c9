#include "dirt/version.h"

#include "core/version_commit.h"

#define DIRT_STR_(x) #x
#define DIRT_STR(x) DIRT_STR_(x)

const char *dirt_version(void)
{
    return DIRT_STR(DIRT_VERSION_MAJOR) "." DIRT_STR(DIRT_VERSION_MINOR) "." DIRT_STR(
        DIRT_VERSION_PATCH);
}

const char *dirt_version_commit(void)
{
    return DIRT_VERSION_COMMIT;
}
