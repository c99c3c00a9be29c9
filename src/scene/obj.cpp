/* DIRT engine: Wavefront OBJ + MTL loader. tinyobjloader parses the text
 * (faces kept as polygons); this code validates every index, triangulates
 * the polygons itself (n corners -> n - 2 triangles, ear clipping in the
 * polygon's plane), and maps the MTL materials onto the metallic-roughness
 * model (doc/scenes.md has the mapping). Like the glTF loader it trusts
 * nothing in the file: a bad index or a non-finite position ends the load
 * with an error, never with a crash; what has no equivalent in the model
 * warns once per kind. */
#include "scene/scene_internal.h"
#include "scene/cpp_alloc.hpp"

#include "dirt/log.h"

#include <stb_image.h>
#include <strings.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <sstream>
#include <streambuf>
#include <string>
#include <unordered_map>
#include <vector>

namespace {

/* The budget of the load in progress on this thread (scene_charge). */
bool charge(size_t count, size_t each, const char *what)
{
    return scene_charge(count, each, what);
}

using dirt_scene_cpp::alloc_zeroed;
using dirt_scene_cpp::decode_rgba8;
using dirt_scene_cpp::dup_array;

/* A read-only stream buffer over bytes in memory (no copy). */
struct MemBuf : std::streambuf {
    MemBuf(const char *p, size_t n)
    {
        char *b = const_cast<char *>(p);
        setg(b, b, b + n);
    }
};

/* A message quoting what a file says, fit to print: bytes outside
 * printable ASCII shown as '?', at most 200 bytes. */
std::string printable(const std::string &text)
{
    std::string t = text.size() > 200 ? text.substr(0, 197) + "..." : text;
    for (char &c : t) {
        if ((unsigned char)c < 32 || (unsigned char)c > 126)
            c = '?';
    }
    return t;
}

std::string file_stem(const std::string &path)
{
    size_t slash = path.find_last_of('/');
    std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
    size_t dot = base.find_last_of('.');
    return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

std::string dir_of(const std::string &path)
{
    size_t slash = path.find_last_of('/');
    if (slash == std::string::npos)
        return ".";
    return slash == 0 ? "/" : path.substr(0, slash);
}

/* A path written in a file, '\' read as '/' (files made on Windows), made
 * relative to `dir` unless absolute. */
std::string resolve(const std::string &dir, std::string name)
{
    std::replace(name.begin(), name.end(), '\\', '/');
    if (!name.empty() && name[0] == '/')
        return name;
    return dir + "/" + name;
}

/* ---- MTL libraries ------------------------------------------------------ */

/* Which statements a material of a library states (tinyobjloader gives
 * every value, with its own defaults where a statement is absent, so an
 * absent Kd and "Kd 0 0 0" look alike there). */
struct MtlStated {
    bool kd = false, ks = false, ke = false, ns = false, pr = false, pm = false;
    bool illum = false;
    bool ni = false, tf = false; /* glass: the index and the filter colour */
};

bool is_space(char c)
{
    return c == ' ' || c == '\t';
}

/* The statements of each material of `text`, in the order tinyobjloader's
 * LoadMtl appends them: its line splitting (LF, CR LF or CR), trimming and
 * keywords, a material per named `newmtl`, and the one being read at the
 * end of the text always. */
void scan_stated(const std::string &text, std::vector<MtlStated> *out)
{
    MtlStated cur;
    bool named = false;
    size_t i = 0, n = text.size();
    while (i < n) {
        size_t end = i;
        while (end < n && text[end] != '\n' && text[end] != '\r')
            end++;
        std::string line = text.substr(i, end - i);
        i = end;
        if (i < n && text[i] == '\r' && i + 1 < n && text[i + 1] == '\n')
            i++;
        if (i < n)
            i++;
        size_t last = line.find_last_not_of(" \t");
        line = last == std::string::npos ? std::string() : line.substr(0, last + 1);
        const char *t = line.c_str();
        t += strspn(t, " \t");
        if (t[0] == '\0' || t[0] == '#')
            continue;
        if (strncmp(t, "newmtl", 6) == 0 && is_space(t[6])) {
            if (named)
                out->push_back(cur);
            cur = MtlStated();
            named = t[7] != '\0';
            continue;
        }
        if (strncmp(t, "illum", 5) == 0 && is_space(t[5])) {
            cur.illum = true;
            continue;
        }
        if (t[0] == '\0' || t[1] == '\0' || !is_space(t[2]))
            continue;
        if (t[0] == 'K' && t[1] == 'd')
            cur.kd = true;
        else if (t[0] == 'K' && t[1] == 's')
            cur.ks = true;
        else if (t[0] == 'K' && t[1] == 'e')
            cur.ke = true;
        else if (t[0] == 'N' && t[1] == 's')
            cur.ns = true;
        else if (t[0] == 'P' && t[1] == 'r')
            cur.pr = true;
        else if (t[0] == 'P' && t[1] == 'm')
            cur.pm = true;
        else if (t[0] == 'N' && t[1] == 'i')
            cur.ni = true;
        else if (t[0] == 'T' && t[1] == 'f')
            cur.tf = true;
    }
    out->push_back(cur);
}

/* What an MTL library costs while it is parsed: its text twice (the
 * bytes, the copy LoadMtl reads), and per newmtl statement LoadMtl's
 * material_t (in a vector that may hold three times its size while it
 * grows) and what the scene makes of it (measured: about 4.5 KiB). */
const size_t mtl_copies = 2, mtl_material_cost = 6144;

/* The newmtl statements of MTL text (each makes a material). */
size_t count_newmtl(const std::string &text)
{
    size_t count = 0;
    for (size_t i = 0; i < text.size(); i++) {
        if (i != 0 && text[i - 1] != '\n' && text[i - 1] != '\r')
            continue;
        size_t j = i;
        while (j < text.size() && (text[j] == ' ' || text[j] == '\t'))
            j++;
        count += text.compare(j, 6, "newmtl") == 0;
    }
    return count;
}

/* Reads the MTL libraries an OBJ names: from files beside it, or the one
 * text a scene loaded from memory comes with. Records, per material, what
 * it states and the directory its texture paths resolve in. */
class MtlReader : public tinyobj::MaterialReader {
public:
    std::string dir;            /* of the .obj; unused from memory */
    bool from_memory = false;
    const std::string *memory_mtl = nullptr; /* from memory: the MTL text, or none */
    bool memory_used = false;
    std::vector<MtlStated> stated;  /* per material, when `stated_ok` */
    std::vector<std::string> tex_dir; /* per material; "" = cannot read files */
    std::string label;

    bool operator()(const std::string &name, std::vector<tinyobj::material_t> *materials,
                    std::map<std::string, int> *map, std::string *warn,
                    std::string *err) override
    {
        std::string text, where;
        if (from_memory) {
            if (!memory_mtl || memory_used) {
                *warn += "mtllib '" + name + "': a scene loaded from memory " +
                         (memory_mtl ? "has one MTL text, already read"
                                     : "has no MTL text to read") + "\n";
                return false;
            }
            memory_used = true;
            text = *memory_mtl;
            if (!scene_charge(count_newmtl(text), mtl_material_cost, "the MTL materials"))
                return false;
        } else {
            std::string path = resolve(dir, name);
            size_t n = 0;
            bool missing = false;
            unsigned char *bytes = scene_read_ref_file(path.c_str(), printable(name).c_str(),
                                                       "mtllib", mtl_copies, &n, &missing);
            if (!bytes) {
                if (missing)
                    *warn += "cannot read the material library '" + printable(path) +
                             "' (" + strerror(ENOENT) + ")\n";
                return false;
            }
            text.assign((const char *)bytes, n);
            free(bytes);
            if (!scene_charge(count_newmtl(text), mtl_material_cost, "the MTL materials"))
                return false;
            where = dir_of(path);
        }
        size_t before = materials->size();
        std::string w;
        MemBuf buf(text.data(), text.size());
        std::istream in(&buf);
        tinyobj::LoadMtl(map, materials, &in, &w, err);
        *warn += w;
        std::vector<MtlStated> s;
        scan_stated(text, &s);
        if (s.size() != materials->size() - before) {
            /* Not read the way LoadMtl read it: take every value as stated. */
            MtlStated all;
            all.kd = all.ks = all.ke = all.ns = all.pr = all.pm = all.illum = true;
            all.ni = all.tf = true;
            s.assign(materials->size() - before, all);
        }
        stated.insert(stated.end(), s.begin(), s.end());
        tex_dir.resize(materials->size(), where);
        return true;
    }
};

/* Warnings gathered while converting, said once per kind at the end: the
 * kind, how many materials (or elements) and the first one's name. */
struct Notes {
    struct Note {
        size_t count = 0;
        std::string first;
    };
    std::map<std::string, Note> notes;
    std::vector<std::string> order;

    void add(const std::string &what, const std::string &who)
    {
        auto it = notes.find(what);
        if (it == notes.end()) {
            order.push_back(what);
            it = notes.emplace(what, Note()).first;
            it->second.first = printable(who);
        }
        it->second.count++;
    }

    void say(const char *label) const
    {
        for (const std::string &k : order) {
            const Note &n = notes.at(k);
            SCENE_WARN("%s: %s (%zu material%s, first '%s')", label, k.c_str(), n.count,
                      n.count == 1 ? "" : "s", n.first.c_str());
        }
    }
};

/* tinyobjloader's messages, one line per distinct message (with a count),
 * at most 12 lines and a count of the rest. */
void log_tinyobj(const char *label, const std::string &text, bool error)
{
    std::vector<std::string> lines;
    std::vector<size_t> counts;
    size_t more = 0, start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos)
            end = text.size();
        std::string line = text.substr(start, end - start);
        start = end + 1;
        if (line.empty() || line == ".")
            continue;
        size_t k = 0;
        while (k < lines.size() && lines[k] != line)
            k++;
        if (k == lines.size()) {
            if (lines.size() >= 12) {
                more++;
                continue;
            }
            lines.push_back(line);
            counts.push_back(0);
        }
        counts[k]++;
    }
    for (size_t k = 0; k < lines.size(); k++) {
        lines[k] = printable(lines[k]);
        if (error)
            DIRT_ERROR("%s: %s", label, lines[k].c_str());
        else if (counts[k] > 1)
            SCENE_WARN("%s: %s (%zu times)", label, lines[k].c_str(), counts[k]);
        else
            SCENE_WARN("%s: %s", label, lines[k].c_str());
    }
    if (more && !error)
        SCENE_WARN("%s: %zu more messages of the OBJ parser", label, more);
}

struct Loader {
    dirt_scene *s = nullptr;
    std::string label;
    const tinyobj::attrib_t *attrib = nullptr;
    const MtlReader *mtl = nullptr;
    std::map<std::pair<std::string, bool>, int> texture_of;
    Notes notes;
};

/* ---- materials ---------------------------------------------------------- */

float finite_or(double x, float fallback)
{
    return std::isfinite(x) ? (float)x : fallback;
}

float clamp01(float x)
{
    return x < 0.0f ? 0.0f : x > 1.0f ? 1.0f : x;
}

float max3(const float *v)
{
    return std::max(v[0], std::max(v[1], v[2]));
}

/* Scene texture of map `name` (already stripped of its options) of material
 * `m`, decoded on first use; DIRT_NO_TEXTURE (counted, noted) when it cannot
 * be read or decoded. Decoded pixels are charged to the budget. Returns -2
 * when the budget is exceeded (a failure of the load). */
int get_texture(Loader &L, size_t m, const std::string &name, bool srgb, const char *slot,
                const char *mat_name)
{
    const std::string &dir = m < L.mtl->tex_dir.size() ? L.mtl->tex_dir[m] : std::string();
    if (dir.empty()) {
        L.notes.add(std::string(slot) + " cannot be read by a scene loaded from memory; "
                    "the factor is used", mat_name);
        L.s->stats.textures_failed++;
        return DIRT_NO_TEXTURE;
    }
    std::string path = resolve(dir, name);
    auto key = std::make_pair(path, srgb);
    auto it = L.texture_of.find(key);
    if (it != L.texture_of.end())
        return it->second;
    int &slot_index = L.texture_of[key];
    slot_index = DIRT_NO_TEXTURE;
    size_t n = 0;
    bool missing = false;
    std::string quoted = printable(name);
    unsigned char *bytes = scene_read_ref_file(path.c_str(), quoted.c_str(), slot, 1, &n, &missing);
    if (!bytes && !missing)
        return -2; /* outside the folder, not a regular file, over the budget: logged */
    if (!bytes) {
        SCENE_WARN("%s: material '%s' %s: cannot read '%s' (%s); using the factor",
                  L.label.c_str(), mat_name, slot, printable(path).c_str(), strerror(ENOENT));
        L.s->stats.textures_failed++;
        return slot_index;
    }
    std::unique_ptr<unsigned char, void (*)(void *)> keep(bytes, free);
    int w = 0, h = 0;
    const char *why = "";
    std::string label = L.label + ": material '" + mat_name + "' " + slot + " '" + quoted + "'";
    int fits = n > (size_t)INT32_MAX ? 0 : dirt_scene_cpp::texture_fits(bytes, n, label.c_str(), &why);
    if (fits < 0)
        return -2;
    uint8_t *rgba = fits ? decode_rgba8(bytes, n, &w, &h, &why) : nullptr;
    if (fits)
        dirt_scene_cpp::texture_decoded(bytes, n, rgba ? w : 0, rgba ? h : 0);
    if (!rgba) {
        SCENE_WARN("%s: material '%s' %s: cannot decode '%s' (%s); using the factor",
                  L.label.c_str(), mat_name, slot, printable(path).c_str(), why);
        L.s->stats.textures_failed++;
        return slot_index;
    }
    dirt_texture *t = &L.s->textures[L.s->num_textures];
    t->width = w;
    t->height = h;
    t->rgba = rgba;
    t->srgb = srgb;
    size_t slash = path.find_last_of('/');
    scene_copy_name(t->name, sizeof(t->name),
                    slash == std::string::npos ? path.c_str() : path.c_str() + slash + 1);
    slot_index = (int)L.s->num_textures++;
    return slot_index;
}

bool texopt_default(const tinyobj::texture_option_t &o)
{
    return o.scale[0] == 1 && o.scale[1] == 1 && o.origin_offset[0] == 0 &&
           o.origin_offset[1] == 0 && !o.clamp && o.brightness == 0 && o.contrast == 1;
}

/* The material an OBJ face gets without one (no MTL, usemtl of a name no
 * library defines): grey diffuse. */
void default_material(dirt_material *d, const char *name)
{
    dirt_material_default(d);
    scene_copy_name(d->name, sizeof(d->name), name);
    d->base_color[0] = d->base_color[1] = d->base_color[2] = 0.8f;
    d->metallic = 0.0f;
}

/* MTL -> metallic-roughness (doc/scenes.md, "MTL materials"). */
bool convert_material(Loader &L, size_t i, const tinyobj::material_t &src, dirt_material *d)
{
    MtlStated st;
    if (i < L.mtl->stated.size())
        st = L.mtl->stated[i];
    std::string name = src.name.empty() ? "material " + std::to_string(i) : src.name;
    const char *nm = name.c_str();
    default_material(d, nm);

    float kd[3], ks[3], ke[3];
    for (int k = 0; k < 3; k++) {
        kd[k] = std::max(0.0f, finite_or(src.diffuse[k], 0.0f));
        ks[k] = std::max(0.0f, finite_or(src.specular[k], 0.0f));
        ke[k] = std::max(0.0f, finite_or(src.emission[k], 0.0f));
    }
    bool has_map_kd = !src.diffuse_texname.empty();
    bool has_map_ke = !src.emissive_texname.empty();
    /* illum 0 and 1 have no specular term; without illum, 2 (highlight). */
    int illum = st.illum ? src.illum : 2;
    bool highlight = illum != 0 && illum != 1;

    /* Base colour: Kd, times map_Kd; map_Kd without Kd is the map alone. */
    for (int k = 0; k < 3; k++)
        d->base_color[k] = has_map_kd && !st.kd ? 1.0f : kd[k];
    /* Metallic: Pm when stated; else a material whose diffuse is black and
     * specular is not (a mirror, a metal) is a metal of colour Ks. */
    if (st.pm) {
        d->metallic = clamp01(finite_or(src.metallic, 0.0f));
    } else if (highlight && !has_map_kd && max3(kd) == 0.0f && max3(ks) > 0.0f) {
        d->metallic = 1.0f;
        for (int k = 0; k < 3; k++)
            d->base_color[k] = ks[k];
    }
    /* Roughness: Pr when stated; else from Ns (Blinn-Phong exponent ->
     * Beckmann/GGX alpha = sqrt(2 / (Ns + 2)), roughness = sqrt(alpha)),
     * 1 when there is no highlight (black or absent Ks, illum 0/1). */
    if (st.pr) {
        d->roughness = clamp01(finite_or(src.roughness, 1.0f));
    } else if (highlight && (max3(ks) > 0.0f || d->metallic > 0.0f)) {
        float ns = st.ns ? std::max(0.0f, finite_or(src.shininess, 0.0f)) : 0.0f;
        d->roughness = clamp01(std::pow(2.0f / (ns + 2.0f), 0.25f));
    }
    /* Emission: Ke, times map_Ke; map_Ke without Ke is the map alone. */
    for (int k = 0; k < 3; k++)
        d->emissive[k] = has_map_ke && !st.ke ? 1.0f : ke[k];

    if (has_map_kd) {
        int t = get_texture(L, i, src.diffuse_texname, true, "map_Kd", nm);
        if (t == -2)
            return false;
        d->base_color_tex = t;
        if (!texopt_default(src.diffuse_texopt))
            L.notes.add("map_Kd options (-s, -o, -clamp, -mm) ignored", name);
    }
    if (has_map_ke) {
        int t = get_texture(L, i, src.emissive_texname, true, "map_Ke", nm);
        if (t == -2)
            return false;
        d->emissive_tex = t;
        if (!texopt_default(src.emissive_texopt))
            L.notes.add("map_Ke options (-s, -o, -clamp, -mm) ignored", name);
    }

    /* Glass (illum 4, 6, 7, 9: transparency or refraction on): a clear
     * dielectric (KHR_materials_transmission 1) of index Ni when stated (and
     * >= 1), tinted by the filter colour Tf when stated (else clear), not
     * metallic; the highlight's roughness as above. Opaque materials keep
     * ior 1.5: exporters write "Ni 1" by default, which would remove their
     * reflection (F0 0). */
    if (illum == 4 || illum == 6 || illum == 7 || illum == 9) {
        d->transmission = 1.0f;
        d->metallic = 0.0f;
        for (int k = 0; k < 3; k++)
            d->base_color[k] = st.tf ? clamp01(finite_or(src.transmittance[k], 1.0f)) : 1.0f;
        if (st.ni) {
            float ni = finite_or(src.ior, 1.5f);
            if (ni >= 1.0f)
                d->ior = ni;
            else
                L.notes.add("Ni below 1 ignored (ior 1.5)", name);
        }
        if (has_map_kd)
            L.notes.add("map_Kd of a glass material tints its transmission", name);
    }
    /* What the model has no place for. */
    if (illum == 10)
        L.notes.add("illum 10 (shadow matte) is not supported", name);
    else if (illum < 0 || illum > 10)
        L.notes.add("unknown illum " + std::to_string(illum) + " read as illum 2", name);
    /* Dissolve (doc/scenes.md): d (or 1 - Tr) below 1 is BLEND coverage
     * (stochastic transparency) with that alpha; map_d naming map_Kd's own
     * image is that texture's alpha channel (coverage = d * alpha). */
    float dissolve = finite_or(src.dissolve, 1.0f);
    bool map_d_kd = !src.alpha_texname.empty() && has_map_kd &&
                    src.alpha_texname == src.diffuse_texname;
    bool glass = d->transmission > 0.0f;
    if (glass && (dissolve < 1.0f || map_d_kd)) {
        /* A glass's transparency is its transmission: its d is not also
         * coverage (that would let light through twice). */
        L.notes.add("d / Tr of a glass material ignored: its transmission is its "
                    "transparency", name);
    } else if (dissolve < 1.0f || map_d_kd) {
        d->alpha_mode = DIRT_ALPHA_BLEND;
        d->base_color[3] = clamp01(dissolve);
    }
    /* norm: a tangent-space normal map (linear RGB, as glTF's), its -bm
     * the normal scale; bump / map_bump are height maps, which the model
     * has no place for. */
    if (!src.normal_texname.empty()) {
        int t = get_texture(L, i, src.normal_texname, false, "norm", nm);
        if (t == -2)
            return false;
        d->normal_tex = t;
        float bm = finite_or(src.normal_texopt.bump_multiplier, 1.0f);
        d->normal_scale = bm;
        if (!texopt_default(src.normal_texopt))
            L.notes.add("norm options (-s, -o, -clamp, -mm) ignored", name);
    }
    if (!src.bump_texname.empty())
        L.notes.add("bump / map_bump (height) maps ignored (norm, a tangent-space normal map, "
                    "is read)", name);
    if (!src.specular_texname.empty() || !src.specular_highlight_texname.empty())
        L.notes.add("map_Ks / map_Ns ignored", name);
    if (!src.alpha_texname.empty() && !map_d_kd)
        L.notes.add("map_d ignored unless it names the map_Kd image (whose alpha is then the "
                    "coverage)", name);
    if (!src.displacement_texname.empty() || !src.reflection_texname.empty())
        L.notes.add("disp / refl maps ignored", name);
    if (!src.roughness_texname.empty() || !src.metallic_texname.empty() ||
        !src.sheen_texname.empty())
        L.notes.add("map_Pr / map_Pm / map_Ps ignored (their factors are used)", name);
    if (src.sheen != 0 || src.clearcoat_thickness != 0 || src.anisotropy != 0)
        L.notes.add("sheen / clearcoat / anisotropy ignored", name);
    /* Not quoted: an unknown statement may be any line of any file (an
     * mtllib that names /etc/passwd, allowed outside the folder). */
    if (!src.unknown_parameter.empty())
        L.notes.add("unknown MTL statements ignored", name);
    return true;
}

/* ---- polygons ----------------------------------------------------------- */

/* Triangulates the polygon `pos` (n >= 3 corners, in order) into n - 2
 * triangles of corner numbers appended to `out`: ear clipping in the plane
 * of the polygon's Newell normal, starting each search at the second
 * remaining corner (a convex polygon becomes the fan from corner 0); when
 * no ear is found, or the work exceeds about 4 n^2 steps, the rest is a fan. */
void triangulate(const std::vector<const float *> &pos, std::vector<uint32_t> *out)
{
    size_t n = pos.size();
    std::vector<uint32_t> r(n);
    for (size_t k = 0; k < n; k++)
        r[k] = (uint32_t)k;
    if (n > 3) {
        double nx = 0, ny = 0, nz = 0;
        for (size_t k = 0; k < n; k++) {
            const float *a = pos[k], *b = pos[(k + 1) % n];
            nx += ((double)a[1] - b[1]) * ((double)a[2] + b[2]);
            ny += ((double)a[2] - b[2]) * ((double)a[0] + b[0]);
            nz += ((double)a[0] - b[0]) * ((double)a[1] + b[1]);
        }
        double ax = std::fabs(nx), ay = std::fabs(ny), az = std::fabs(nz);
        /* Project along the dominant axis, keeping the orientation. */
        int u = 1, v = 2;
        double sign = nx;
        if (ay >= ax && ay >= az) {
            u = 2, v = 0, sign = ny;
        } else if (az >= ax && az >= ay) {
            u = 0, v = 1, sign = nz;
        }
        bool planar = std::isfinite(sign) && sign != 0.0;
        double orient = sign > 0 ? 1.0 : -1.0;
        auto cross2 = [&](uint32_t a, uint32_t b, uint32_t c) {
            const float *pa = pos[a], *pb = pos[b], *pc = pos[c];
            return orient * (((double)pb[u] - pa[u]) * ((double)pc[v] - pa[v]) -
                             ((double)pb[v] - pa[v]) * ((double)pc[u] - pa[u]));
        };
        size_t work = 0, limit = 4 * n * n;
        while (planar && r.size() > 3 && work < limit) {
            size_t m = r.size();
            bool found = false;
            for (size_t k = 0; k < m && !found && work < limit; k++) {
                uint32_t a = r[k], b = r[(k + 1) % m], c = r[(k + 2) % m];
                work++;
                if (!(cross2(a, b, c) > 0.0))
                    continue; /* reflex or degenerate corner */
                bool inside = false;
                for (size_t j = 0; j < m && !inside; j++) {
                    uint32_t p = r[j];
                    work++;
                    if (p == a || p == b || p == c)
                        continue;
                    inside = cross2(a, b, p) > 0.0 && cross2(b, c, p) > 0.0 &&
                             cross2(c, a, p) > 0.0;
                }
                if (inside)
                    continue;
                out->insert(out->end(), {a, b, c});
                r.erase(r.begin() + (ptrdiff_t)((k + 1) % m));
                found = true;
            }
            if (!found)
                break;
        }
    }
    for (size_t k = 1; k + 1 < r.size(); k++)
        out->insert(out->end(), {r[0], r[k], r[k + 1]});
}

/* ---- the mesh ----------------------------------------------------------- */

struct Corner {
    int v, vt, vn;
    bool operator==(const Corner &o) const { return v == o.v && vt == o.vt && vn == o.vn; }
};

struct CornerHash {
    size_t operator()(const Corner &c) const
    {
        uint64_t h = (uint64_t)(uint32_t)c.v * 0x9E3779B97F4A7C15ull;
        h ^= (uint64_t)(uint32_t)c.vt + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
        h ^= (uint64_t)(uint32_t)c.vn + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
        return (size_t)h;
    }
};

/* One primitive under construction: a run of faces of one material. */
struct PrimBuild {
    uint32_t material = 0;
    std::vector<float> pos, nrm, uv;
    bool any_normal = false, any_uv = false;
    std::vector<uint32_t> idx;
    std::unordered_map<Corner, uint32_t, CornerHash> vertex_of;
};

/* What an entry of PrimBuild::vertex_of holds (a hash node and its bucket). */
const size_t corner_map_cost = 64;

/* Vertex of corner `c` in `p`, made on first use (position checked
 * finite, normal zero when absent or not finite: flat at evaluation, UV
 * (u, 1 - v) so that OBJ's bottom-left origin matches glTF's top-left).
 * UINT32_MAX on an error (logged). */
uint32_t corner_vertex(Loader &L, PrimBuild &p, const Corner &c, const char *what)
{
    auto it = p.vertex_of.find(c);
    if (it != p.vertex_of.end())
        return it->second;
    const tinyobj::attrib_t &a = *L.attrib;
    const float *x = &a.vertices[3 * (size_t)c.v];
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2])) {
        SCENE_FAIL(NOT_FINITE, "%s: vertex %d has a non-finite (NaN/Inf) position", what,
                   c.v + 1);
        return UINT32_MAX;
    }
    /* its position, normal, uv, and its entry in vertex_of */
    if (!charge(1, sizeof(float[8]) + corner_map_cost, what))
        return UINT32_MAX;
    uint32_t id = (uint32_t)(p.pos.size() / 3);
    p.pos.insert(p.pos.end(), x, x + 3);
    float n[3] = {0.0f, 0.0f, 0.0f};
    if (c.vn >= 0) {
        const float *y = &a.normals[3 * (size_t)c.vn];
        if (std::isfinite(y[0]) && std::isfinite(y[1]) && std::isfinite(y[2])) {
            memcpy(n, y, sizeof(n));
            p.any_normal = true;
        }
    }
    p.nrm.insert(p.nrm.end(), n, n + 3);
    float uv[2] = {0.0f, 0.0f};
    if (c.vt >= 0) {
        const float *t = &a.texcoords[2 * (size_t)c.vt];
        uv[0] = std::isfinite(t[0]) ? t[0] : 0.0f;
        uv[1] = std::isfinite(t[1]) ? 1.0f - t[1] : 0.0f;
        p.any_uv = true;
    }
    p.uv.insert(p.uv.end(), uv, uv + 2);
    p.vertex_of.emplace(c, id);
    return id;
}

/* Moves a finished primitive into the scene mesh (counted first, so that a
 * failure frees it). */
void finish_prim(scene_mesh *mesh, PrimBuild &b)
{
    scene_prim *pr = &mesh->prims[mesh->num_prims++];
    pr->material = b.material;
    pr->num_vertices = b.pos.size() / 3;
    pr->position = (float(*)[3])dup_array(b.pos);
    if (b.any_normal)
        pr->normal = (float(*)[3])dup_array(b.nrm);
    if (b.any_uv)
        pr->uv = (float(*)[2])dup_array(b.uv);
    pr->num_triangles = b.idx.size() / 3;
    pr->indices = dup_array(b.idx);
    mesh->num_triangles += pr->num_triangles;
    b = PrimBuild();
}

bool convert(Loader &L, const std::vector<tinyobj::shape_t> &shapes,
             const std::vector<tinyobj::material_t> &mats)
{
    dirt_scene *s = L.s;
    const tinyobj::attrib_t &a = *L.attrib;
    const char *label = L.label.c_str();
    size_t nv = a.vertices.size() / 3, nn = a.normals.size() / 3, nt = a.texcoords.size() / 2;
    if (nv > (size_t)INT32_MAX || nn > (size_t)INT32_MAX || nt > (size_t)INT32_MAX) {
        SCENE_FAIL(TOO_LARGE, "%s: too many vertices", label);
        return false;
    }

    /* Faces, triangles and runs of one material; every face's corner count
     * adds up to the shape's indices (a face of 256 corners or more cannot
     * be told from tinyobjloader's 8-bit counts). */
    size_t triangles = 0, runs = 0, lines = 0, points = 0;
    long last_mat = -2;
    bool need_default = false;
    for (const tinyobj::shape_t &sh : shapes) {
        const tinyobj::mesh_t &m = sh.mesh;
        size_t corners = 0;
        if (m.material_ids.size() != m.num_face_vertices.size()) {
            SCENE_FAIL(INVALID, "%s: shape '%s': %zu faces with %zu materials", label,
                       sh.name.c_str(), m.num_face_vertices.size(), m.material_ids.size());
            return false;
        }
        for (size_t f = 0; f < m.num_face_vertices.size(); f++) {
            size_t k = m.num_face_vertices[f];
            corners += k;
            if (k >= 3)
                triangles += k - 2;
            int mat = m.material_ids[f];
            if (mat < 0 || (size_t)mat >= mats.size()) {
                need_default = true;
                mat = -1;
            }
            if (mat != last_mat)
                runs++;
            last_mat = mat;
        }
        if (corners != m.indices.size()) {
            SCENE_FAIL(INVALID, "%s: shape '%s': a face has more than 255 corners (%zu "
                       "indices for the faces' %zu corners)", label, sh.name.c_str(),
                       m.indices.size(), corners);
            return false;
        }
        lines += sh.lines.num_line_vertices.size();
        points += sh.points.indices.size();
    }
    if (lines || points)
        SCENE_WARN("%s: %zu line and %zu point elements ignored (triangles only)", label,
                  lines, points);
    if (triangles > SCENE_MAX_COUNT) {
        SCENE_FAIL(TOO_LARGE, "%s: too many triangles (%zu)", label, triangles);
        return false;
    }
    /* (The triangles' indices and frame were charged by the scan.) */

    s->materials = alloc_zeroed<dirt_material>(mats.size() + 1);
    s->textures = alloc_zeroed<dirt_texture>(mats.size() * 2);
    for (size_t i = 0; i < mats.size(); i++) {
        if (!convert_material(L, i, mats[i], &s->materials[i]))
            return false;
        s->num_materials = i + 1;
    }
    uint32_t default_mat = (uint32_t)mats.size();
    if (need_default || mats.empty()) {
        default_material(&s->materials[mats.size()], "default");
        s->num_materials = mats.size() + 1;
    }
    L.notes.say(label);

    s->meshes = alloc_zeroed<scene_mesh>(1);
    s->num_meshes = 1;
    scene_mesh *mesh = &s->meshes[0];
    scene_copy_name(mesh->name, sizeof(mesh->name), s->name);
    mesh->prims = alloc_zeroed<scene_prim>(runs);
    mesh->weights = alloc_zeroed<float>(0);

    PrimBuild cur;
    bool open = false;
    size_t face_no = 0;
    std::vector<const float *> poly;
    std::vector<uint32_t> local, tri;
    for (const tinyobj::shape_t &sh : shapes) {
        const tinyobj::mesh_t &m = sh.mesh;
        size_t off = 0;
        for (size_t f = 0; f < m.num_face_vertices.size(); f++) {
            size_t k = m.num_face_vertices[f];
            const tinyobj::index_t *ix = m.indices.data() + off;
            off += k;
            face_no++;
            int mi = m.material_ids[f];
            uint32_t mat = mi < 0 || (size_t)mi >= mats.size() ? default_mat : (uint32_t)mi;
            if (k < 3)
                continue;
            char what[320];
            snprintf(what, sizeof(what), "%s: face %zu (group '%s')", label, face_no,
                     sh.name.c_str());
            poly.clear();
            for (size_t c = 0; c < k; c++) {
                const tinyobj::index_t &q = ix[c];
                /* Indices as tinyobjloader resolved them (0-based; relative
                 * ones from the end of what precedes the face; -1 = none for
                 * normals and texture coordinates). */
                const char *bad = nullptr;
                long at = 0;
                size_t have = 0;
                if (q.vertex_index < 0 || (size_t)q.vertex_index >= nv)
                    bad = "vertex", at = q.vertex_index, have = nv;
                else if (q.normal_index < -1 ||
                         (q.normal_index >= 0 && (size_t)q.normal_index >= nn))
                    bad = "normal", at = q.normal_index, have = nn;
                else if (q.texcoord_index < -1 ||
                         (q.texcoord_index >= 0 && (size_t)q.texcoord_index >= nt))
                    bad = "texture coordinate", at = q.texcoord_index, have = nt;
                if (bad) {
                    if (at < 0)
                        SCENE_FAIL(INDEX, "%s: corner %zu: the %s index points before the "
                                   "first %s", what, c + 1, bad, bad);
                    else
                        SCENE_FAIL(INDEX, "%s: corner %zu: %s %ld does not exist (the file "
                                   "has %zu)", what, c + 1, bad, at + 1, have);
                    return false;
                }
                poly.push_back(&a.vertices[3 * (size_t)q.vertex_index]);
            }
            if (open && cur.material != mat) {
                finish_prim(mesh, cur);
                open = false;
            }
            if (!open) {
                cur.material = mat;
                open = true;
            }
            local.clear();
            for (size_t c = 0; c < k; c++) {
                Corner cn = {ix[c].vertex_index, ix[c].texcoord_index, ix[c].normal_index};
                uint32_t id = corner_vertex(L, cur, cn, what);
                if (id == UINT32_MAX)
                    return false;
                local.push_back(id);
            }
            tri.clear();
            triangulate(poly, &tri);
            for (uint32_t t : tri)
                cur.idx.push_back(local[t]);
        }
    }
    if (open)
        finish_prim(mesh, cur);

    s->nodes = alloc_zeroed<scene_node>(1);
    s->num_nodes = 1;
    scene_node *node = &s->nodes[0];
    scene_copy_name(node->name, sizeof(node->name), s->name);
    node->parent = -1;
    node->mesh = 0;
    node->skin = node->camera = node->light = -1;
    node->rotation[3] = 1.0f;
    node->scale[0] = node->scale[1] = node->scale[2] = 1.0f;
    /* Normal maps need tangents: OBJ has none, they are generated. */
    for (size_t p = 0; p < mesh->num_prims; p++) {
        scene_prim *pr = &mesh->prims[p];
        if (!pr->uv || pr->material >= s->num_materials ||
            s->materials[pr->material].normal_tex == DIRT_NO_TEXTURE)
            continue;
        if (!charge(pr->num_vertices, sizeof(float[4]), "the OBJ tangents"))
            return false;
        if (!scene_prim_generate_tangents(pr))
            throw std::bad_alloc();
    }
    return scene_finalize(s, nullptr, 0);
}

/* Destroys the scene under construction unless released. */
struct SceneGuard {
    dirt_scene *s;
    ~SceneGuard() { dirt_scene_destroy(s); }
    dirt_scene *release()
    {
        dirt_scene *r = s;
        s = nullptr;
        return r;
    }
};

/* Loads OBJ `text` (owned: tag lines are blanked in place) with `reader`
 * for its mtllib statements. */
/* What a scan of the OBJ text finds before tinyobjloader parses it: the
 * statements that cost the parser memory, and the coordinates it would
 * misread (tinyobjloader reads "nan" and "inf" as 0, and an index past
 * 2^31 wraps to another vertex). */
struct ObjScan {
    size_t v = 0, vn = 0, vt = 0, faces = 0, corners = 0, other = 0;
    size_t triangles = 0; /* of the faces of 3 corners or more: corners - 2 */
    /* (element, component) of v, vn, vt coordinates written as nan or inf */
    std::vector<std::pair<size_t, int>> nonfinite[3];
};

/* What tinyobjloader holds while it parses, per statement (bytes, measured
 * against its peak: doc/scenes.md, "Memory"): a vertex's coordinates and
 * colours, a face's record, corner list and its copy into the shape (all in
 * vectors that may hold twice their size while they grow), a group or any
 * other statement's shape or name. */
const size_t obj_cost_v = 64, obj_cost_vn = 32, obj_cost_vt = 24, obj_cost_face = 128,
             obj_cost_corner = 24, obj_cost_other = 256;

bool space(char c)
{
    return c == ' ' || c == '\t';
}

/* Scans `text` line by line as tinyobjloader splits it (LF, CR LF or CR):
 * counts statements; records v/vn/vt coordinates written as nan or inf
 * (any case, signed); fails (logged) on a coordinate that is not a number
 * (SYNTAX) and on a face, line or point index outside the 32-bit range
 * tinyobjloader reads (INDEX). */
bool scan_obj(const std::string &text, const char *label, ObjScan *out)
{
    size_t i = 0, n = text.size(), line = 0;
    const char *t = text.data();
    while (i < n) {
        size_t end = i;
        while (end < n && t[end] != '\n' && t[end] != '\r')
            end++;
        line++;
        size_t p = i;
        i = end;
        if (i < n && t[i] == '\r' && i + 1 < n && t[i + 1] == '\n')
            i++;
        if (i < n)
            i++;
        while (p < end && space(t[p]))
            p++;
        if (p >= end || t[p] == '#')
            continue;
        int kind = -1; /* 0 v, 1 vn, 2 vt */
        if (t[p] == 'v' && p + 1 < end && space(t[p + 1]))
            kind = 0, p += 2;
        else if (t[p] == 'v' && p + 2 < end && t[p + 1] == 'n' && space(t[p + 2]))
            kind = 1, p += 3;
        else if (t[p] == 'v' && p + 2 < end && t[p + 1] == 't' && space(t[p + 2]))
            kind = 2, p += 3;
        if (kind >= 0) {
            size_t &count = kind == 0 ? out->v : kind == 1 ? out->vn : out->vt;
            int want = kind == 2 ? 2 : 3;
            for (int c = 0; c < want; c++) {
                while (p < end && space(t[p]))
                    p++;
                size_t q = p;
                while (q < end && !space(t[q]))
                    q++;
                std::string tok(t + p, q - p);
                p = q;
                if (tok.empty() && kind == 2 && c == 1)
                    break; /* "vt u": v reads as 0 */
                const char *s = tok.c_str();
                if (*s == '+' || *s == '-')
                    s++;
                bool nonfinite = !strncasecmp(s, "nan", 3) || !strncasecmp(s, "inf", 3);
                char *stop = nullptr;
                if (!tok.empty())
                    strtod(tok.c_str(), &stop);
                if (nonfinite) {
                    out->nonfinite[kind].push_back({count, c});
                } else if (tok.empty() || stop == tok.c_str()) {
                    SCENE_FAIL(SYNTAX, "%s: line %zu: a %s coordinate that is not a number", label,
                               line, kind == 0 ? "v" : kind == 1 ? "vn" : "vt");
                    return false;
                }
            }
            count++;
            continue;
        }
        bool face = t[p] == 'f' && p + 1 < end && space(t[p + 1]);
        bool element = (t[p] == 'l' || t[p] == 'p') && p + 1 < end && space(t[p + 1]);
        if (!face && !element) {
            out->other++;
            continue;
        }
        p += 2;
        if (face)
            out->faces++;
        else
            out->other++;
        size_t face_corners = 0;
        while (p < end) {
            while (p < end && space(t[p]))
                p++;
            if (p >= end)
                break;
            out->corners += face;
            face_corners += face;
            /* v[/vt][/vn]: each number as atoi reads it */
            while (p < end && !space(t[p])) {
                size_t q = p;
                if (q < end && (t[q] == '+' || t[q] == '-'))
                    q++;
                size_t digits = q;
                long long v = 0;
                bool big = false;
                while (q < end && t[q] >= '0' && t[q] <= '9') {
                    v = v * 10 + (t[q] - '0');
                    big |= v > 2147483647LL;
                    if (big)
                        v = 2147483648LL;
                    q++;
                }
                if (big) {
                    SCENE_FAIL(INDEX, "%s: line %zu: an index of %zu digits, past the largest "
                               "(2147483647) the OBJ parser reads", label, line, q - digits);
                    return false;
                }
                while (q < end && !space(t[q]) && t[q] != '/')
                    q++;
                p = q < end && t[q] == '/' ? q + 1 : q;
            }
        }
        if (face_corners >= 3)
            out->triangles += face_corners - 2;
    }
    return true;
}

/* Loads OBJ `text` (owned: tag lines are blanked in place) with `reader`
 * for its mtllib statements. */
dirt_scene *load_text(std::string &text, MtlReader &reader, const char *label)
{
    if (text.empty()) {
        SCENE_FAIL(EMPTY, "'%s' is empty", label);
        return nullptr;
    }
    /* Tag statements ("t", subdivision creases) are of no use here and
     * cost tinyobjloader up to 8192 values each however short the line:
     * made comments before it sees them. */
    for (size_t i = 0; i < text.size(); i++) {
        if (i == 0 || text[i - 1] == '\n' || text[i - 1] == '\r') {
            size_t j = i;
            while (j < text.size() && (text[j] == ' ' || text[j] == '\t'))
                j++;
            if (j + 1 < text.size() && text[j] == 't' && (text[j + 1] == ' ' || text[j + 1] == '\t'))
                text[j] = '#';
        }
    }
    ObjScan scan;
    if (!scan_obj(text, label, &scan))
        return nullptr;
    std::string what = std::string("'") + label + "': the OBJ parser's arrays";
    /* The triangles' indices, and one evaluated frame of them (as for glTF:
     * 3 corners x (position, normal, uv) + material and instance), before
     * anything is parsed. */
    const size_t frame_bytes =
        3 * (sizeof(float[3]) * 2 + sizeof(float[2])) + 2 * sizeof(uint32_t);
    std::string tris = std::string("'") + label + "': the OBJ triangles";
    if (scan.triangles > SCENE_MAX_COUNT) {
        SCENE_FAIL(TOO_LARGE, "%s: too many triangles (%zu)", label, scan.triangles);
        return nullptr;
    }
    if (!charge(scan.triangles, 3 * sizeof(uint32_t) + frame_bytes, tris.c_str()))
        return nullptr;
    if (!charge(scan.v, obj_cost_v, what.c_str()) || !charge(scan.vn, obj_cost_vn, what.c_str()) ||
        !charge(scan.vt, obj_cost_vt, what.c_str()) ||
        !charge(scan.faces, obj_cost_face, what.c_str()) ||
        !charge(scan.corners, obj_cost_corner, what.c_str()) ||
        !charge(scan.other, obj_cost_other, what.c_str()))
        return nullptr;
    reader.label = label;
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> mats;
    std::string warn, err;
    MemBuf buf(text.data(), text.size());
    std::istream in(&buf);
    bool ok = tinyobj::LoadObj(&attrib, &shapes, &mats, &warn, &err, &in, &reader,
                               /*triangulate=*/false, /*default_vcols_fallback=*/false);
    log_tinyobj(label, warn, false);
    /* An MTL library refused (outside the folder, not a regular file, over
     * the budget) fails the load. */
    if (scene_error_get() != DIRT_SCENE_ERR_OK) {
        DIRT_ERROR("cannot load '%s'", label);
        return nullptr;
    }
    if (!ok) {
        scene_set_error(err.find("index") != std::string::npos ? DIRT_SCENE_ERR_INDEX
                                                               : DIRT_SCENE_ERR_SYNTAX);
        log_tinyobj(label, err.empty() ? std::string("tinyobjloader could not parse the file")
                                       : err, true);
        DIRT_ERROR("cannot load '%s'", label);
        return nullptr;
    }
    if (!err.empty())
        log_tinyobj(label, err, false);
    text.clear();
    text.shrink_to_fit();
    /* nan and inf, which tinyobjloader read as 0, are what they say: a
     * face using such a position fails (NOT_FINITE), such a normal or
     * texture coordinate counts as absent. */
    std::vector<float> *arrays[3] = {&attrib.vertices, &attrib.normals, &attrib.texcoords};
    for (int k = 0; k < 3; k++) {
        size_t width = k == 2 ? 2 : 3;
        for (const auto &nf : scan.nonfinite[k]) {
            size_t at = nf.first * width + (size_t)nf.second;
            if (at < arrays[k]->size())
                (*arrays[k])[at] = NAN;
        }
    }
    SceneGuard guard{scene_new(file_stem(label).c_str())};
    if (!guard.s)
        return nullptr;
    Loader L;
    L.s = guard.s;
    L.label = label;
    L.attrib = &attrib;
    L.mtl = &reader;
    if (!convert(L, shapes, mats)) {
        DIRT_ERROR("cannot load '%s'", label);
        return nullptr;
    }
    return guard.release();
}

dirt_scene *load(const char *path)
{
    size_t n = 0;
    unsigned char *bytes = scene_read_scene_file(path, 1, &n);
    if (!bytes)
        return nullptr;
    std::string text;
    try {
        text.assign((const char *)bytes, n);
    } catch (...) {
        free(bytes);
        throw;
    }
    free(bytes);
    MtlReader reader;
    reader.dir = dir_of(path);
    return load_text(text, reader, path);
}

dirt_scene *load_memory(const void *obj, size_t obj_size, const void *mtl, size_t mtl_size,
                        const char *label)
{
    if (!charge(obj_size, 1, "the OBJ text") || !charge(mtl_size, mtl_copies, "the MTL text"))
        return nullptr;
    std::string text((const char *)obj, obj_size);
    std::string mtl_text;
    MtlReader reader;
    reader.from_memory = true;
    if (mtl) {
        mtl_text.assign((const char *)mtl, mtl_size);
        reader.memory_mtl = &mtl_text;
    }
    return load_text(text, reader, label);
}

/* Runs `f` with the budget set and every exception turned into a logged
 * failure. */
template <typename F> dirt_scene *guarded(const char *label, const dirt_load_opts *, F f)
{
    try {
        return f();
    } catch (const std::bad_alloc &) {
        SCENE_FAIL(OUT_OF_MEMORY, "out of memory loading '%s'", label);
    } catch (const std::exception &e) {
        DIRT_ERROR("cannot load '%s': %s", label, e.what());
    } catch (...) {
        DIRT_ERROR("cannot load '%s': unknown error", label);
    }
    return nullptr;
}

} // namespace

extern "C" dirt_scene *scene_load_obj(const char *path, const dirt_load_opts *opts)
{
    return guarded(path, opts, [&] { return load(path); });
}

extern "C" dirt_scene *scene_load_obj_memory(const void *obj, size_t obj_size, const void *mtl,
                                             size_t mtl_size, const char *label,
                                             const dirt_load_opts *opts)
{
    return guarded(label, opts, [&] { return load_memory(obj, obj_size, mtl, mtl_size, label); });
}
