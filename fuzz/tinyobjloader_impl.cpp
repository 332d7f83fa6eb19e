// tinyobjloader_impl.cpp - tinyobjloader compiled into the fuzz targets.
//
// Debian ships tinyobjloader as a shared library built without coverage or
// sanitizer instrumentation, so libFuzzer could not see its branches and ASan
// could not see its memory errors. The fuzz targets compile the same version's
// implementation (from the same header) with instrumentation instead. The
// targets still link rt::rt and so the shared library, but a symbol defined in
// the executable itself takes precedence over the shared library's (ELF symbol
// resolution), so every call goes to this instrumented copy.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
