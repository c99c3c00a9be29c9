"""The DIRT engine from Python: scenes, render sessions, images as numpy arrays.

A thin layer over the consumer API of libdirt.so (include/dirt/session.h and
the headers it includes), called through cffi in ABI mode: the declarations
are generated from those headers at build time (_cdef.h), so every session
option, stats field and error id of the C API is the one here.

    import dirt
    scene = dirt.Scene()                       # the default scene (or Scene("x.glb"))
    s = dirt.Session(scene, engine="dirt", width=64, height=48, seed=3, bounces=2)
    s.add_samples(4)
    beauty = s.image()                         # (48, 64, 4) float32
    depth = s.aov("Z")                         # (48, 64) float32
    print(s.stats()["mrays_per_s"])
    s.write("out.exr")

Every session option of dirt_session_opts is a keyword of Session() and
set_options(); enums are given by name ("dirt", "cube_camera", "ao", ...)
or number, `background` as three floats, `env` as a dirt.Env, a file name
or "sky". Unknown keywords raise TypeError, bad values ValueError. A failing
engine call raises dirt.Error with the engine's error id (`err.id`, e.g.
"TOO_DEEP" from the scene loader or "CAMERA" from the session).

The GPU engines share one headless OpenGL context (EGL), made on the first
session that needs it, current on the thread that made it: use the module
from one thread. The environment variable DIRT_LIBRARY names another
libdirt.so to load.
"""
import atexit
import os
import sys
import weakref

import numpy as np
from cffi import FFI

from . import _paths

__all__ = ["Error", "Scene", "Env", "Session", "version", "gpu_description", "ffi", "lib"]

ffi = FFI()
with open(os.path.join(os.path.dirname(__file__), "_cdef.h"), encoding="utf-8") as _f:
    ffi.cdef(_f.read())
# Never unloaded: Embree's worker threads (and the GL driver's) outlive the
# interpreter's last reference, and would run in unmapped code at exit.
lib = ffi.dlopen(os.environ.get("DIRT_LIBRARY") or _paths.LIBRARY,
                 ffi.RTLD_NOW | ffi.RTLD_NODELETE)

__version__ = ffi.string(lib.dirt_version()).decode()


def version():
    """(version, commit) of the loaded library: ("0.1.0", "c8c4d07...")."""
    return __version__, ffi.string(lib.dirt_version_commit()).decode()


# ---- errors and the log -----------------------------------------------------

class Error(Exception):
    """A failed engine call. `kind` is "scene" or "session", `id` the engine's
    error id ("TOO_DEEP", "CAMERA", ...: DIRT_SCENE_ERRORS and
    DIRT_SESSION_ERRORS in the C headers), `code` its number, `reason` the
    engine's own message (the log's last error) or its id's description."""

    def __init__(self, kind, code, id, reason):
        super().__init__("%s error %s: %s" % (kind, id, reason))
        self.kind, self.code, self.id, self.reason = kind, code, id, reason


_last_log_error = [None]
_LEVELS = {lib.DIRT_LOG_ERROR: "error", lib.DIRT_LOG_WARN: "warning",
           lib.DIRT_LOG_INFO: "info", lib.DIRT_LOG_DEBUG: "debug"}


@ffi.callback("void(void *, enum dirt_log_level, const char *, int, const char *)")
def _on_log(user, level, file, line, msg):
    text = ffi.string(msg).decode(errors="replace")
    if level == lib.DIRT_LOG_ERROR:
        _last_log_error[0] = text
    if file != ffi.NULL:
        where = ffi.string(file).decode(errors="replace")
        cut = where.find("src/")
        sys.stderr.write("dirt: %s: %s:%d: %s\n" % (_LEVELS.get(level, "?"),
                                                     where[cut:] if cut >= 0 else where,
                                                     line, text))
    else:
        sys.stderr.write("dirt: %s\n" % text)


lib.dirt_log_set_callback(_on_log, ffi.NULL)


def _raise(kind):
    if kind == "scene":
        code = lib.dirt_scene_last_error()
        name, desc = lib.dirt_scene_error_name(code), lib.dirt_scene_error_str(code)
    else:
        code = lib.dirt_session_last_error()
        name, desc = lib.dirt_session_error_name(code), lib.dirt_session_error_str(code)
    reason = _last_log_error[0] or ffi.string(desc).decode()
    _last_log_error[0] = None
    raise Error(kind, int(code), ffi.string(name).decode(), reason)


def _begin():
    _last_log_error[0] = None


# ---- enums by name ----------------------------------------------------------

def _enum_names(ctype):
    """{"dirt": 0, ...} of an enum type: its enumerators without their common
    prefix, lower case (the count enumerators, *_NUM_*, left out)."""
    names = [n for n in ctype.relements if "_NUM_" not in n]
    prefix = os.path.commonprefix(names)
    prefix = prefix[:prefix.rfind("_") + 1]
    return {n[len(prefix):].lower(): ctype.relements[n] for n in names}


def _enum_value(field, ctype, value):
    names = _enum_names(ctype)
    if isinstance(value, str):
        key = value.lower().replace("-", "_").replace("+", "_")
        if key not in names:
            raise ValueError("%s: %r is not one of %s" % (field, value, ", ".join(names)))
        return names[key]
    if isinstance(value, bool) or not isinstance(value, int) or value not in names.values():
        raise ValueError("%s: %r is not one of %s" % (field, value, ", ".join(names)))
    return value


def _enum_name(ctype, value):
    for name, v in _enum_names(ctype).items():
        if v == value:
            return name
    return int(value)


# ---- scenes and environments ------------------------------------------------

class Scene:
    """A scene: the default scene (no path), or a glTF 2.0 (.gltf, .glb) or
    OBJ file. max_bytes and max_depth bound the load (dirt_load_opts; 0 =
    the defaults); strict turns every warning about the scene into a
    failure (STRICT); allow_outside lets the scene read files outside its
    folder (else OUTSIDE). Raises Error (kind "scene") with the loader's
    id."""

    def __init__(self, path=None, max_bytes=0, max_depth=0, strict=False, allow_outside=False):
        _begin()
        if path is None:
            ptr = lib.dirt_scene_create_default()
        else:
            opts = ffi.new("dirt_load_opts *", {"max_bytes": max_bytes, "max_depth": max_depth,
                                                "strict": strict, "allow_outside": allow_outside})
            ptr = lib.dirt_scene_load(os.fsencode(path), opts)
        if ptr == ffi.NULL:
            _raise("scene")
        self._ptr = ffi.gc(ptr, lib.dirt_scene_destroy)

    @property
    def name(self):
        return ffi.string(lib.dirt_scene_name(self._ptr)).decode()

    @property
    def triangles(self):
        return int(lib.dirt_scene_num_triangles(self._ptr))

    @property
    def cameras(self):
        """Names of the scene's cameras (index = camera number)."""
        defs = lib.dirt_scene_cameras(self._ptr)
        return [ffi.string(defs[i].name).decode()
                for i in range(lib.dirt_scene_num_cameras(self._ptr))]

    @property
    def clips(self):
        """{name: duration in seconds} of the animation clips, in order."""
        return {ffi.string(lib.dirt_scene_clip_name(self._ptr, i)).decode():
                float(lib.dirt_scene_clip_duration(self._ptr, i))
                for i in range(lib.dirt_scene_num_clips(self._ptr))}


class Env:
    """An environment light: an equirectangular .exr or .hdr file, or "sky"
    (the built-in sky); intensity scales it (0 = 1), rotation turns it about
    +Y in degrees. Raises ValueError when it cannot be read."""

    def __init__(self, path, intensity=0.0, rotation=0.0):
        opts = ffi.new("dirt_env_opts *", {"intensity": intensity, "rotation": rotation})
        why = ffi.new("char[256]")
        ptr = lib.dirt_env_load(os.fsencode(path), opts, why, 256)
        if ptr == ffi.NULL:
            raise ValueError("environment %s: %s" % (path, ffi.string(why).decode()))
        self._ptr = ffi.gc(ptr, lib.dirt_env_destroy)


# ---- the GPU ---------------------------------------------------------------

class _Gpu:
    def __init__(self):
        self.ptr = lib.dirt_gpu_create(ffi.new("dirt_gpu_opts *"))

    def close(self):
        if self.ptr != ffi.NULL:
            lib.dirt_gpu_destroy(self.ptr)
            self.ptr = ffi.NULL


_gpu = None
_sessions = weakref.WeakSet()


def _the_gpu():
    global _gpu
    if _gpu is None:
        _begin()
        _gpu = _Gpu()
    return _gpu


def gpu_description():
    """The GL renderer and platform in use (made on demand), or None when
    no OpenGL 4.5 context can be had."""
    g = _the_gpu()
    if g.ptr == ffi.NULL:
        return None
    buf = ffi.new("char[512]")
    lib.dirt_gpu_describe(g.ptr, buf, 512)
    return ffi.string(buf).decode()


@atexit.register
def _shutdown():
    for s in list(_sessions):
        s.close()
    if _gpu is not None:
        _gpu.close()


# ---- sessions --------------------------------------------------------------

_OPTS = ffi.typeof("dirt_session_opts")
_OPTION_NAMES = [name for name, _ in _OPTS.fields]


class Session:
    """A render session (dirt_session) on `scene` through `engine` ("dirt",
    "mmrt", "embree", "raster"), with any option of dirt_session_opts as a
    keyword (width, height, seed, bounces, mode, views, tile_size, ...; zero
    or absent = the engine's default). The GPU engines use the module's
    headless GPU; embree runs on the CPU. Raises Error (kind "session":
    OPTION, NO_GPU, ...) when the session cannot be made."""

    def __init__(self, scene, engine="dirt", **options):
        if not isinstance(scene, Scene):
            raise TypeError("scene must be a dirt.Scene")
        self._ptr = ffi.NULL
        self._scene = scene
        self._env = self._env_next = None
        opts = self._opts(dict(options, engine=engine), ffi.new("dirt_session_opts *"))
        gpu = ffi.NULL
        if opts.engine != lib.DIRT_ENGINE_EMBREE:
            gpu = _the_gpu().ptr
        self._gpu = _gpu
        _begin()
        ptr = lib.dirt_session_create(gpu, scene._ptr, opts)
        if ptr == ffi.NULL:
            _raise("session")
        self._ptr = ptr
        self._env = self._env_next  # borrowed by the session: kept alive with it
        _sessions.add(self)

    # options
    def _opts(self, options, out):
        for key, value in options.items():
            if key not in _OPTION_NAMES:
                raise TypeError("unknown session option %r (options: %s)"
                                % (key, ", ".join(_OPTION_NAMES)))
            ctype = dict(_OPTS.fields)[key].type
            if key == "env":
                if value is None:
                    env = None
                elif isinstance(value, Env):
                    env = value
                elif isinstance(value, (str, os.PathLike)):
                    env = Env(value)
                else:
                    raise ValueError("env: a dirt.Env, a file name or \"sky\"")
                out.env = env._ptr if env else ffi.NULL
                self._env_next = env
            elif ctype.kind == "enum":
                setattr(out, key, _enum_value(key, ctype, value))
            elif ctype.kind == "array":
                seq = list(value)
                if len(seq) != ctype.length:
                    raise ValueError("%s: %d values, not %d" % (key, ctype.length, len(seq)))
                getattr(out, key)[0:ctype.length] = [float(v) for v in seq]
            elif ctype.cname == "_Bool":
                setattr(out, key, bool(value))
            elif ctype.cname in ("float", "double"):
                if isinstance(value, bool) or not isinstance(value, (int, float)):
                    raise ValueError("%s: a number, not %r" % (key, value))
                setattr(out, key, float(value))
            else:
                if isinstance(value, bool) or not isinstance(value, int):
                    raise ValueError("%s: an integer, not %r" % (key, value))
                try:
                    setattr(out, key, value)
                except OverflowError:
                    raise ValueError("%s: %r is out of range" % (key, value)) from None
        return out

    @property
    def options(self):
        """The session's options as a dict (enums by name)."""
        o = lib.dirt_session_get_opts(self._live())
        return {name: _value(getattr(o, name), f.type) for name, f in _OPTS.fields
                if name != "env"}

    def set_options(self, **options):
        """Changes options (the others stay); True when the accumulation
        restarted. Raises like Session()."""
        new = ffi.new("dirt_session_opts *")
        new[0] = lib.dirt_session_get_opts(self._live())[0]
        self._env_next = self._env
        self._opts(options, new)
        restarted = ffi.new("bool *")
        _begin()
        if not lib.dirt_session_set_opts(self._ptr, new, restarted):
            _raise("session")
        self._env = self._env_next
        return bool(restarted[0])

    # time, camera, samples
    def set_time(self, t, clip=0, loop=False, all_clips=False):
        """Evaluates the scene at t seconds of animation clip `clip` (-1: the
        rest pose); restarts the accumulation."""
        ev = ffi.new("dirt_eval_opts *", {"clip": clip, "loop": loop, "all_clips": all_clips})
        _begin()
        if not lib.dirt_session_set_time(self._live(), float(t), ev):
            _raise("session")

    def set_camera(self, camera="default", eye=None, target=None, up=(0.0, 1.0, 0.0),
                   fov=45.0, znear=0.0, zfar=0.0):
        """Looks through scene camera `camera` (an index), "default" (camera 0,
        or automatic without cameras) or "auto" (frames the whole clip); with
        eye and target, through that pinhole camera (fov: vertical degrees;
        the numbers dirt-render's --eye/--look-at/--up/--fov take)."""
        cam = ffi.NULL
        index = 0
        if eye is not None or target is not None:
            look = ffi.new("dirt_camera_look *", {"eye": list(eye), "target": list(target),
                                                  "up": list(up), "fov_deg": fov,
                                                  "znear": znear, "zfar": zfar})
            cam = ffi.new("dirt_camera *")
            lib.dirt_camera_from_look(look, cam)
            choice = lib.DIRT_CAMERA_EXPLICIT
        elif camera == "default":
            choice = lib.DIRT_CAMERA_DEFAULT
        elif camera == "auto":
            choice = lib.DIRT_CAMERA_AUTO
        elif isinstance(camera, int) and not isinstance(camera, bool):
            choice, index = lib.DIRT_CAMERA_SCENE, camera
        else:
            raise ValueError("camera: an index, \"default\" or \"auto\", or eye= and target=")
        _begin()
        if not lib.dirt_session_set_camera(self._live(), choice, index, cam):
            _raise("session")

    def add_samples(self, n=1):
        """Adds n samples per pixel to the accumulation (the raster engine
        renders its preview once)."""
        _begin()
        if not lib.dirt_session_add_samples(self._live(), int(n), ffi.NULL, ffi.NULL):
            _raise("session")

    def advance(self, budget_ms=0.0):
        """Works on the next sample for about budget_ms milliseconds (0: one
        smallest piece) and returns whether this call completed it; a
        sample may span many calls, and N samples made so equal
        add_samples(N) bit for bit (dirt_session_advance). Meanwhile
        samples, image() and the rest give the completed samples."""
        _begin()
        done = ffi.new("bool *")
        if not lib.dirt_session_advance(self._live(), float(budget_ms), done):
            _raise("session")
        return bool(done[0])

    @property
    def sample_part(self):
        """The part of the sample in progress done, in [0, 1) (0: none)."""
        return float(lib.dirt_session_sample_part(self._live()))

    def reset(self):
        """Restarts the accumulation (0 samples)."""
        lib.dirt_session_reset(self._live())

    @property
    def samples(self):
        return int(lib.dirt_session_samples(self._live()))

    @property
    def size(self):
        """(width, height) in use (the height follows the camera's aspect
        when the options leave it 0)."""
        w, h = ffi.new("int *"), ffi.new("int *")
        lib.dirt_session_size(self._live(), w, h)
        return int(w[0]), int(h[0])

    # results
    def _image(self):
        _begin()
        img = lib.dirt_session_image(self._live())
        if img == ffi.NULL:
            _raise("session")
        return img

    def image(self):
        """The accumulated beauty (the mean radiance): a new float32 array of
        height x width x 4 (RGBA, row 0 = the top)."""
        img = self._image()
        w, h = img.width, img.height
        return np.frombuffer(ffi.buffer(img.rgba, w * h * 4 * 4), dtype=np.float32) \
            .reshape(h, w, 4).copy()

    def aovs(self):
        """Names of the image's extra channels ("albedo.R", ..., "Z", "ID")."""
        img = self._image()
        return [ffi.string(img.channels[i].name).decode() for i in range(img.channel_count)]

    def aov(self, name):
        """An extra channel as a new float32 array of height x width ("Z",
        "ID", "albedo.R", ...), or a group of them as height x width x 3
        ("albedo": R, G, B; "N": X, Y, Z). KeyError when the engine has no
        such channel (aovs() lists them)."""
        img = self._image()
        w, h = img.width, img.height
        planes = {ffi.string(img.channels[i].name).decode(): img.channels[i].data
                  for i in range(img.channel_count)}

        def plane(n):
            return np.frombuffer(ffi.buffer(planes[n], w * h * 4), dtype=np.float32) \
                .reshape(h, w).copy()
        if name in planes:
            return plane(name)
        group = sorted((n for n in planes if n.rsplit(".", 1)[0] == name),
                       key=lambda n: "RGBAXYZW".find(n.rsplit(".", 1)[-1]))
        if not group:
            raise KeyError("no channel %r (the image has %s)" % (name, ", ".join(planes)))
        return np.stack([plane(n) for n in group], axis=-1)

    def stats(self):
        """The figures of the accumulation (dirt_session_stats) as a dict:
        times in ms with the clock that measured them, rays, bytes per
        buffer, the paths at each event, the structure's own figures under
        "ads" (dirt) or "mmrt"."""
        st = lib.dirt_session_get_stats(self._live())
        d = _value(st[0], ffi.typeof("dirt_session_stats"))
        d["passes"] = d["passes"][:st.num_passes]
        d["buffers"] = d["buffers"][:st.num_buffers]
        d["paths_at_event"] = d["paths_at_event"][:st.events + 1]
        del d["num_passes"], d["num_buffers"]
        for key in ("ads", "mmrt"):
            if not d.pop("has_" + key):
                del d[key]
        return d

    def write(self, path, half=False, exposure=0.0, tonemap="clamp"):
        """Writes the image to .exr (beauty and AOVs; half: 16-bit floats) or
        .png (8-bit sRGB after exposure in stops and the tone map "clamp",
        "reinhard" or "aces"), atomically."""
        o = ffi.new("dirt_image_write_options *")
        o.exr.half_rgba = o.exr.half_extra = bool(half)
        o.png.exposure = float(exposure)
        o.png.tonemap = _enum_value("tonemap", ffi.typeof("enum dirt_tonemap"), tonemap)
        _begin()
        if not lib.dirt_session_write_image(self._live(), os.fsencode(path), o):
            _raise("session")

    # lifetime
    def _live(self):
        if self._ptr == ffi.NULL:
            raise ValueError("the session is closed")
        return self._ptr

    def close(self):
        """Frees the session now (also when garbage-collected)."""
        if self._ptr != ffi.NULL:
            lib.dirt_session_destroy(self._ptr)
            self._ptr = ffi.NULL

    def __del__(self):
        self.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _value(cdata, ctype):
    """A C value as Python: structs as dicts, arrays as lists, char arrays
    and strings as str, enums by name."""
    kind = ctype.kind
    if kind == "struct":
        return {name: _value(getattr(cdata, name), f.type) for name, f in ctype.fields}
    if kind == "array":
        if ctype.item.cname == "char":
            return ffi.string(cdata).decode(errors="replace")
        return [_value(cdata[i], ctype.item) for i in range(ctype.length)]
    if kind == "pointer":
        if ctype.item.cname == "char":
            return ffi.string(cdata).decode(errors="replace") if cdata != ffi.NULL else None
        return None
    if kind == "enum":
        return _enum_name(ctype, cdata)
    return cdata
