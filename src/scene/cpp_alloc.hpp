/* Allocation helpers of the scene layer's C++ loaders (gltf.cpp, obj.cpp):
 * C heap arrays (freed by the C side with free()) that throw
 * std::bad_alloc on failure, for the loaders' one catch. */
#ifndef DIRT_SCENE_CPP_ALLOC_HPP
#define DIRT_SCENE_CPP_ALLOC_HPP

#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

namespace dirt_scene_cpp {

/* A malloc'd copy of `v` (at least one element's room). */
template <typename T> T *dup_array(const std::vector<T> &v)
{
    T *p = (T *)malloc((v.empty() ? 1 : v.size()) * sizeof(T));
    if (!p)
        throw std::bad_alloc();
    if (!v.empty())
        memcpy(p, v.data(), v.size() * sizeof(T));
    return p;
}

/* n zeroed elements (at least one's room). */
template <typename T> T *alloc_zeroed(size_t n)
{
    T *p = (T *)calloc(n ? n : 1, sizeof(T));
    if (!p)
        throw std::bad_alloc();
    return p;
}

} // namespace dirt_scene_cpp

#endif
