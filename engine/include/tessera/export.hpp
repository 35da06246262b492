// TESSERA_API marks the declarations of the public API that a shared Tessera library exports.
// A shared build compiles the library with hidden visibility (-fvisibility=hidden,
// -fvisibility-inlines-hidden), so only what carries this mark is in its dynamic symbol table:
// the internal namespaces (tessera::detail, tessera::fast, tessera::simd, ...) are not. In a
// static build the mark changes nothing. GCC and Clang on ELF platforms only: the build uses
// their flags and does not produce Windows DLLs, which would need dllexport/dllimport here.
#pragma once

#if defined(__GNUC__) || defined(__clang__)
#define TESSERA_API __attribute__((visibility("default")))
#else
#define TESSERA_API
#endif
