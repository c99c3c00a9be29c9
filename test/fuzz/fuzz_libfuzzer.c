/* DIRT engine: the libFuzzer driver of the fuzz targets (clang
 * -fsanitize=fuzzer,address,undefined; built with -Dfuzz=true), one
 * program per entry: DIRT_FUZZ_ENTRY names it (dirt_fuzz_scene_one by
 * default; fuzz_inputs.h has the others). Run:
 *   fuzz_replay --write corpus && fuzz_scene corpus/scene -max_total_time=60
 * (./dirt.sh fuzz SECONDS runs every target, doc/fuzzing.md). */
#include "fuzz_inputs.h"
#include "fuzz_scene.h"

#ifndef DIRT_FUZZ_ENTRY
#define DIRT_FUZZ_ENTRY dirt_fuzz_scene_one
#endif

#include "dirt/log.h"

#include <stdlib.h>

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void quiet(void *user, enum dirt_log_level level, const char *file, int line,
                  const char *msg)
{
    (void)user, (void)level, (void)file, (void)line, (void)msg;
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc, (void)argv;
    dirt_log_set_callback(quiet, NULL);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!DIRT_FUZZ_ENTRY(data, size))
        abort(); /* an invariant broke: libFuzzer saves the input */
    return 0;
}
