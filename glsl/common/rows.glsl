// A one-dimensional launch made in rows of DIRT_GROUPS_ROW groups of
// DIRT_GROUP_SIZE (gl_dispatch_rows on the host; GL promises only 65535
// groups per dimension): group (x, y) is number y * DIRT_GROUPS_ROW + x.
// Needs common/constants.h. The caller bound-checks the index.
uint dirt_row_invocation()
{
    return (gl_WorkGroupID.y * uint(DIRT_GROUPS_ROW) + gl_WorkGroupID.x) * uint(DIRT_GROUP_SIZE) +
           gl_LocalInvocationID.x;
}
