/* DIRT engine: the views an image-space acceleration structure is built in,
 * and their tile frusta. CPU math shared by the GPU build (which uploads
 * these matrices), the trace, and the CPU reference checks.
 *
 * Conventions: eye space looks down -Z; clip = proj * view * world (OpenGL,
 * NDC depth in [-1, 1]); every view is a perspective view, so a point's
 * eye-space depth (distance along the view axis) is its clip-space w.
 * Tile (tx, ty) of a view with tile size S covers pixels [tx*S, tx*S+S) x
 * [ty*S, ty*S+S) clamped to the view, with pixel row 0 at the bottom (GL
 * window coordinates). */
#ifndef DIRT_VIEWS_H
#define DIRT_VIEWS_H

#include <stdbool.h>

#include "dirt/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

#define DIRT_MAX_VIEWS 7
#define DIRT_MAX_MIP_LEVELS 16

enum dirt_view_mode {
    DIRT_VIEWS_SINGLE = 0,       /* the camera view only */
    DIRT_VIEWS_CUBE = 1,         /* six 90 degree faces around the camera */
    DIRT_VIEWS_CUBE_CAMERA = 2,  /* camera view first, then the six faces */
};

/* Cube faces in GL order: +X, -X, +Y, -Y, +Z, -Z. */
enum { DIRT_FACE_POS_X, DIRT_FACE_NEG_X, DIRT_FACE_POS_Y, DIRT_FACE_NEG_Y,
       DIRT_FACE_POS_Z, DIRT_FACE_NEG_Z };

typedef struct dirt_view {
    int face;                /* -1 camera view, else DIRT_FACE_* */
    float eye[3];            /* centre of projection, world space */
    float forward[3];        /* view axis (eye looks along it) */
    float view[16];          /* world -> eye, column-major */
    float proj[16];          /* eye -> clip, column-major */
    float view_proj[16];     /* proj * view */
    float znear, zfar;       /* eye-space depth range of the view */
    int width, height;       /* pixels */
    int tiles_x, tiles_y;    /* ceil(width / S), ceil(height / S) */
    int num_levels;          /* Hi-Z pyramid levels, level 0 = tiles */
    int tile_base;           /* first global tile index of this view */
    int atlas_x;             /* x offset (in tiles) in the build's raster atlas */
} dirt_view;

typedef struct dirt_view_set {
    int count;
    int tile_size;           /* S */
    int camera_view;         /* index of the camera view, or -1 */
    int num_tiles;           /* sum of tiles_x * tiles_y over the views */
    int atlas_width, atlas_height; /* tiles: views side by side */
    int num_levels;          /* max over views */
    /* level_base[d][v]: first entry of view v at level d of the Hi-Z pyramid,
     * levels stored one after the other, views inside a level in order;
     * level sizes are ceil(size / 2^d). */
    int level_base[DIRT_MAX_MIP_LEVELS][DIRT_MAX_VIEWS];
    int pyramid_size;        /* entries of the whole pyramid */
    dirt_view views[DIRT_MAX_VIEWS];
} dirt_view_set;

/* Zero-initialised = single camera view, 640x480, S = 2, faces of
 * max(width, height) / 2 pixels. */
typedef struct dirt_view_opts {
    enum dirt_view_mode mode;
    int width, height;       /* camera view pixels (default 640x480) */
    int face_size;           /* cube face pixels (default max(width,height)/2) */
    int tile_size;           /* S in {1, 2, 4, 8} (default 2) */
} dirt_view_opts;

/* Builds the views around `cam` for a scene whose bounds are [bmin, bmax]:
 * far planes reach the farthest bounds corner; cube faces are 90 degree
 * views whose centre of projection is pulled back from the camera by their
 * near distance, so their near planes pass through the camera position and
 * nothing between camera and near plane is lost (MMRT paper, 3.2).
 * Fails (false, logged) on a bad tile size or size, an orthographic camera
 * for a camera view, or an atlas wider than `max_atlas_width` tiles (0 = no
 * limit). */
bool dirt_views_setup(dirt_view_set *out, const dirt_camera *cam, const float bmin[3],
                      const float bmax[3], const dirt_view_opts *opts, int max_atlas_width);

/* NDC rectangle of tile (tx, ty) of view v: out = {x0, x1, y0, y1}. */
void dirt_view_tile_ndc(const dirt_view *v, int tile_size, int tx, int ty, double out[4]);

/* Clips the world-space triangle `p` against the frustum of tile (tx, ty) of
 * view v, with every plane moved outwards by `eps` (side planes: eps tile
 * widths; near/far: eps in NDC depth). Returns true when the clipped polygon
 * is non-empty (a point or a segment counts), with its eye-space depth range
 * in *zmin, *zmax. Double precision: this is the reference. */
bool dirt_clip_triangle_tile(const dirt_view *v, int tile_size, int tx, int ty,
                             const float p[3][3], double eps, double *zmin, double *zmax);

/* dirt_clip_triangle_tile, and also the NDC bounding box of the clipped
 * polygon's projection in box = {xmin, xmax, ymin, ymax} (box may be NULL). */
bool dirt_clip_triangle_tile_box(const dirt_view *v, int tile_size, int tx, int ty,
                                 const float p[3][3], double eps, double *zmin, double *zmax,
                                 double box[4]);

/* Conservative tile rectangle of a triangle in view v: the tiles its
 * near-clipped projection's bounding box touches, widened by `margin` tiles,
 * clamped to the view. False when the triangle is entirely outside the view
 * frustum (then no tile can have a non-empty clip). */
bool dirt_triangle_tile_rect(const dirt_view *v, int tile_size, const float p[3][3],
                             double margin, int rect[4]);

/* Eye-space depth of a world point in view v (distance along its axis). */
double dirt_view_depth(const dirt_view *v, const float p[3]);

#ifdef __cplusplus
}
#endif
#endif
