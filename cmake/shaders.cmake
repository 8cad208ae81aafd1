# Compiles GLSL compute shaders to SPIR-V with glslangValidator, validates the result with
# spirv-val, and embeds it as a uint32_t array in a generated header <spirv/<name>.h> that
# declares `inline constexpr uint32_t k<Name>Spv[]`. Never commit SPIR-V: it is a build output.
set(VSGL_SPIRV_DIR ${CMAKE_BINARY_DIR}/generated)

function(vsgl_compile_shader out_var source)
  get_filename_component(name ${source} NAME_WE)
  set(spv ${VSGL_SPIRV_DIR}/spirv/${name}.spv)
  set(header ${VSGL_SPIRV_DIR}/spirv/${name}.h)
  # The .spv comes first: glslang's depfile names it, and Ninja matches a depfile against the
  # first output (otherwise every build would recompile every shader).
  add_custom_command(
    OUTPUT ${spv} ${header}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${VSGL_SPIRV_DIR}/spirv
    COMMAND ${GLSLANG_VALIDATOR} --quiet --target-env vulkan1.3 -I${CMAKE_SOURCE_DIR}/shaders
            --depfile ${spv}.d -o ${spv} ${source}
    COMMAND ${SPIRV_VAL} --target-env vulkan1.3 ${spv}
    COMMAND ${CMAKE_COMMAND} -DSPV=${spv} -DHEADER=${header} -DNAME=${name}
            -P ${CMAKE_SOURCE_DIR}/cmake/embed_spirv.cmake
    MAIN_DEPENDENCY ${source}
    DEPFILE ${spv}.d
    COMMENT "GLSL -> SPIR-V ${name}"
    VERBATIM)
  set(${out_var} ${header} PARENT_SCOPE)
endfunction()
