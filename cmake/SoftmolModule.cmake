# cmake/SoftmolModule.cmake — softmol_add_module(): one static library per module folder,
# aliased softmol::<name>, includable as "<name>/file.h" from the repository root. Compiled as
# position-independent code, since libsoftmol.so (api/) is linked from them; without semantic
# interposition, so -fPIC inlines and calls as the executables' -fPIE code did.
function(softmol_position_independent target)
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_compile_options(${target} PRIVATE -fno-semantic-interposition)
endfunction()

function(softmol_add_module)
  cmake_parse_arguments(M "" "NAME" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(softmol_${M_NAME} STATIC ${M_SOURCES})
  add_library(softmol::${M_NAME} ALIAS softmol_${M_NAME})
  target_include_directories(softmol_${M_NAME} PUBLIC ${PROJECT_SOURCE_DIR})
  target_compile_features(softmol_${M_NAME} PUBLIC cxx_std_20)
  softmol_position_independent(softmol_${M_NAME})
  target_link_libraries(softmol_${M_NAME}
    PUBLIC ${M_PUBLIC_DEPS}
    PRIVATE ${M_PRIVATE_DEPS} softmol::warnings)
endfunction()
