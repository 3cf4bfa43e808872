# candela_embed_files(TARGET <lib> NAMESPACE <ns> FILES <abs paths...>)
# Builds a static library holding every file's bytes, looked up by base name
# with  std::string_view <ns>::find(std::string_view name)  (empty if absent).
set(CANDELA_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/embed_files_gen.cmake)
function(candela_embed_files)
  cmake_parse_arguments(E "" "TARGET;NAMESPACE" "FILES" ${ARGN})
  set(out ${CMAKE_CURRENT_BINARY_DIR}/${E_TARGET}_embedded.cpp)
  string(REPLACE ";" "|" files_arg "${E_FILES}")
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DNS=${E_NAMESPACE} "-DFILES=${files_arg}"
            -P ${CANDELA_EMBED_SCRIPT}
    DEPENDS ${E_FILES} ${CANDELA_EMBED_SCRIPT}
    COMMENT "Embedding ${E_TARGET}"
    VERBATIM)
  add_library(${E_TARGET} STATIC ${out})
endfunction()
