# h4_debian_architecture(VAR): Debian's name for the architecture the build targets (amd64,
# arm64, armhf), for the packages' Architecture field. A cross build names its target
# processor; a native build asks dpkg (the processor name where there is no dpkg).
include_guard(GLOBAL)

function(h4_debian_architecture var)
  if(CMAKE_CROSSCOMPILING)
    if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(aarch64|arm64)$")
      set(arch arm64)
    elseif(CMAKE_SYSTEM_PROCESSOR MATCHES "^arm")
      set(arch armhf)
    elseif(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64)$")
      set(arch amd64)
    else()
      message(FATAL_ERROR "no Debian architecture for ${CMAKE_SYSTEM_PROCESSOR}")
    endif()
  else()
    find_program(H4_DPKG dpkg)
    if(H4_DPKG)
      execute_process(COMMAND ${H4_DPKG} --print-architecture OUTPUT_VARIABLE arch
                      OUTPUT_STRIP_TRAILING_WHITESPACE)
    else()
      set(arch ${CMAKE_SYSTEM_PROCESSOR})
    endif()
  endif()
  set(${var} ${arch} PARENT_SCOPE)
endfunction()
