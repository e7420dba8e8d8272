/* Symbol export for the public API. Every public function declaration is marked GD_API.
 *
 *   building the library:   GD_BUILDING_LIBRARY is defined (the build does it);
 *   using the shared one:   nothing to define;
 *   using the static one:   define GD_STATIC (CMake's geardyn::geardyn_static does).
 *
 * GCC and Clang: default visibility, so the symbol stays exported when the library is
 * compiled with -fvisibility=hidden. Windows: dllexport while building the DLL,
 * dllimport when using it. Static consumers: empty.
 *
 * Nothing here allocates or keeps state.
 */
#ifndef GEARDYN_EXPORT_H
#define GEARDYN_EXPORT_H

#if defined(GD_STATIC)
#define GD_API
#elif defined(_WIN32) || defined(__CYGWIN__)
#if defined(GD_BUILDING_LIBRARY)
#define GD_API __declspec(dllexport)
#else
#define GD_API __declspec(dllimport)
#endif
#elif defined(__GNUC__) && __GNUC__ >= 4
#define GD_API __attribute__((visibility("default")))
#else
#define GD_API
#endif

#endif
