/* DIRT engine: the scene fuzz target's entry and its seed corpus, shared by
 * the libFuzzer driver (fuzz_libfuzzer.c, clang -fsanitize=fuzzer) and the
 * replay test that runs in every `meson test` (fuzz_replay.c). */
#ifndef DIRT_FUZZ_SCENE_H
#define DIRT_FUZZ_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Loads `size` bytes from memory (budget 64 MiB) as dirt_fuzz_load does,
 * then, when
 * they load, evaluates every clip (at most 4, and the rest pose, and all
 * clips at once) at a few times, looped and clamped, and the clip bounds.
 * Returns false when an invariant breaks (a failed load without an error
 * id, a frame whose counts disagree with the scene): the driver aborts on
 * it. Crashes, leaks and undefined behaviour are the sanitizers' to find. */
bool dirt_fuzz_scene_one(const uint8_t *data, size_t size);

/* The load of the fuzz entry: bytes starting with '#' are an OBJ (a comment
 * line first), its text up to the first NUL byte and the MTL text after it
 * (dirt_scene_load_obj_memory); anything else a .gltf/.glb
 * (dirt_scene_load_memory). Budget 64 MiB. */
struct dirt_scene *dirt_fuzz_load(const uint8_t *data, size_t size);

/* Writes the seed corpus (small valid and invalid .gltf/.glb files made
 * here, none copied) into the existing directory `dir`; returns how many
 * files, or -1 on a write error (printed). */
int dirt_fuzz_write_corpus(const char *dir);

#endif
