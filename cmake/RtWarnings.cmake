# Warning flags for rt's own programs and tests (never for consumers).
# -Werror is added only by the dev/ci presets (RT_WERROR), never by default.
option(RT_WERROR "Treat warnings as errors in rt's own targets" OFF)
option(RT_SANITIZE "Build rt's own targets with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)

add_library(rt_warnings INTERFACE)
if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  target_compile_options(rt_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wconversion-null)
  if(RT_WERROR)
    target_compile_options(rt_warnings INTERFACE -Werror)
  endif()
  if(RT_SANITIZE)
    target_compile_options(rt_warnings INTERFACE -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
    target_link_options(rt_warnings INTERFACE -fsanitize=address,undefined -fno-sanitize-recover=all)
  endif()
elseif(MSVC)
  target_compile_options(rt_warnings INTERFACE /W4 $<$<BOOL:${RT_WERROR}>:/WX>)
endif()
