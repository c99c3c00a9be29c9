/* DIRT engine: the mark of the consumer API.
 *
 * libdirt.so exports exactly the functions and data that the installed
 * headers (include/dirt/) declare: each such declaration starts with
 * DIRT_API, the engine is compiled with hidden symbol visibility, and the
 * library's version script (src/dirt.map) keeps everything else (C++
 * runtime instantiations, static third-party code) local. Internal headers
 * never use DIRT_API. Test `library_symbols` compares the library's dynamic
 * symbols with the declarations of the installed headers. */
#ifndef DIRT_API_H
#define DIRT_API_H

#if defined(__GNUC__) || defined(__clang__)
#define DIRT_API __attribute__((visibility("default")))
#else
#define DIRT_API
#endif

#endif
