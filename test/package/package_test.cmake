# The installable package, end to end (cmake -P): install the build tree into a fresh prefix, check
# the layout and that installed headers include only installed headers, then configure, build and
# run test/package/consumer against the prefix alone (find_package(claspplan CONFIG REQUIRED)), and
# run the installed program on an installed robot model.
# Then the API example (examples/plan_from_depth.cpp) is built the same way and plans a verified
# clasp from shipped depth files.
#   -DBUILD_DIR=<claspplan build> -DCONSUMER_DIR=<test/package/consumer> -DWORK_DIR=<scratch>
#   -DAPI_EXAMPLE=<examples/plan_from_depth.cpp> -DDEPTH_DIR=<examples/depth/bag_2>
#   -DGENERATOR=... -DBUILD_TYPE=... -DCXX_COMPILER=... -DC_COMPILER=... [-DLAUNCHER=ccache]
#   [-DPYTHON=<interpreter>: the installed Python package is imported too]
cmake_minimum_required(VERSION 3.16)

foreach(var BUILD_DIR CONSUMER_DIR WORK_DIR GENERATOR CXX_COMPILER C_COMPILER API_EXAMPLE DEPTH_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "package_test: -D${var}=... missing")
  endif()
endforeach()
if(NOT BUILD_TYPE)
  set(BUILD_TYPE Release)
endif()

set(prefix "${WORK_DIR}/prefix")
set(consumer_build "${WORK_DIR}/consumer-build")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# Runs a command; on failure prints its output and fails. OUT receives stdout + stderr.
function(run_checked what out)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE output ERROR_VARIABLE output
                  WORKING_DIRECTORY "${WORK_DIR}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "package_test: ${what} failed (${rc}):\n${output}")
  endif()
  set(${out} "${output}" PARENT_SCOPE)
endfunction()

# 1. Install.
run_checked("cmake --install" install_log "${CMAKE_COMMAND}" --install "${BUILD_DIR}"
            --prefix "${prefix}" --config "${BUILD_TYPE}")

# 2. The layout.
set(expected bin/claspplan libexec/claspplan/claspplan-commands
    lib/cmake/claspplan/claspplanConfig.cmake
    lib/cmake/claspplan/claspplanConfigVersion.cmake lib/cmake/claspplan/claspplanTargets.cmake
    include/claspplan/tsrrt/clasp_setup.hpp)
foreach(lib core robots perception servo tsrrt)
  list(APPEND expected lib/libclaspplan_${lib}.a)
endforeach()
foreach(robot kr5_sdh kr5_dlr kr5_icub kr5_armar3)
  list(APPEND expected share/claspplan/robots/${robot}.urdf share/claspplan/robots/${robot}.yaml)
endforeach()
foreach(f IN LISTS expected)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "package_test: ${f} not installed")
  endif()
endforeach()
# Internal headers stay out (CMakeLists.txt, claspplan_export_library).
foreach(f robots/embedded_models.hpp robots/triangle_tree.hpp perception/point_index.hpp
        tsrrt/task_tree.hpp tsrrt/elapsed.hpp core/file_io_detail.hpp core/parallel.hpp
        core/png_files.hpp core/random_draws.hpp)
  if(EXISTS "${prefix}/include/claspplan/${f}")
    message(FATAL_ERROR "package_test: the internal header ${f} is installed")
  endif()
endforeach()

# 2b. The Python package, when it was built (-DPYTHON=<its interpreter>): imported from the prefix
# alone, outside the source and build trees (newlines, not semicolons: CMake splits on those).
if(PYTHON)
  run_checked("import claspplan from the prefix" python_log "${CMAKE_COMMAND}" -E env
              "PYTHONPATH=${prefix}/lib/python3/dist-packages" "${PYTHON}" -c
              "import claspplan\nassert claspplan.__file__.startswith('${prefix}')\nprint(claspplan.Robot('kr5_sdh').dof)")
  if(NOT python_log MATCHES "^12")
    message(FATAL_ERROR "package_test: the installed Python package printed '${python_log}'")
  endif()
endif()

# 3. Every installed header's project includes ("folder/name.hpp") are installed too.
file(GLOB_RECURSE headers RELATIVE "${prefix}/include/claspplan" "${prefix}/include/claspplan/*.hpp")
list(LENGTH headers header_count)
set(missing "")
foreach(h IN LISTS headers)
  file(STRINGS "${prefix}/include/claspplan/${h}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\".*" "\\1" inc "${line}")
    if(NOT EXISTS "${prefix}/include/claspplan/${inc}")
      list(APPEND missing "${h} includes ${inc}")
    endif()
  endforeach()
endforeach()
if(missing)
  string(REPLACE ";" "\n  " missing "${missing}")
  message(FATAL_ERROR "package_test: installed headers include headers that are not installed "
                      "(make them public in CMakeLists.txt, claspplan_export_library):\n  ${missing}")
endif()

# 4. The consumer, against the prefix only.
set(launcher_arg "")
if(LAUNCHER)
  set(launcher_arg "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")
endif()
run_checked("configuring the consumer" configure_log "${CMAKE_COMMAND}" -S "${CONSUMER_DIR}"
            -B "${consumer_build}" -G "${GENERATOR}" "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
            "-DCMAKE_PREFIX_PATH=${prefix}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}"
            "-DCMAKE_C_COMPILER=${C_COMPILER}" -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON
            "-DAPI_EXAMPLE=${API_EXAMPLE}"
            ${launcher_arg})
if(NOT configure_log MATCHES "claspplan_DIR: ${prefix}/lib/cmake/claspplan\n")
  message(FATAL_ERROR "package_test: the consumer did not find the installed package:\n"
                      "${configure_log}")
endif()
run_checked("building the consumer" build_log "${CMAKE_COMMAND}" --build "${consumer_build}"
            --config "${BUILD_TYPE}")
find_program(consumer_exe consumer PATHS "${consumer_build}" "${consumer_build}/${BUILD_TYPE}"
             NO_DEFAULT_PATH REQUIRED)
run_checked("running the consumer" consumer_out "${consumer_exe}")
message("${consumer_out}")
set(expected_lines
    "robot kr5_sdh: 6 arm \\+ 6 hand joints"
    "hand size: finger thickness 0\\.0[0-9]+ m, closed aperture 0\\.[0-9]+ m"
    "robot file kr5_dlr: [0-9]+ joints"
    "home in collision: no"
    "ring: [0-9]+ points, beta1 1\n"
    "hopf link: linking number 1, gauss 1\\.000"
    "loop tube: 192 vertices, 384 triangles"
    "plan_clasp without a robot: invalid_argument")
foreach(line IN LISTS expected_lines)
  if(NOT consumer_out MATCHES "${line}")
    message(FATAL_ERROR "package_test: the consumer's output lacks /${line}/")
  endif()
endforeach()

# 5. The API example, built against the prefix, plans a verified clasp from the depth files.
find_program(api_example_exe plan_from_depth PATHS "${consumer_build}"
             "${consumer_build}/${BUILD_TYPE}" NO_DEFAULT_PATH REQUIRED)
run_checked("the API example" api_out "${api_example_exe}" "${DEPTH_DIR}")
if(NOT api_out MATCHES "verified: yes")
  message(FATAL_ERROR "package_test: the API example planned no verified clasp:\n${api_out}")
endif()

# 6. The installed program, on an installed model file (the launcher starts claspplan-commands from
# libexec).
run_checked("the installed claspplan" robot_out "${prefix}/bin/claspplan" robot
            "${prefix}/share/claspplan/robots/kr5_icub.yaml")
if(NOT robot_out MATCHES "^kr5_icub \\(")
  message(FATAL_ERROR "package_test: unexpected output of claspplan robot:\n${robot_out}")
endif()
message("package_test: ${header_count} headers installed; consumer and installed program pass")
