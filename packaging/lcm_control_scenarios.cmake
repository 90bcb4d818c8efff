# lcm_control_add_scenario(NAME FILE [PACKAGE_PATH DIR...] [LABELS L...] [TIMEOUT S]): a scenario file
# (docs/scenarios.md) as a ctest test of the project that calls it. It runs `scenario run FILE` headless in lockstep
# and fails when a check fails or the scenario cannot run; it is skipped when the scenario's `requires:` files are
# absent; its results are also written as JUnit XML to NAME.junit.xml in the calling folder's build folder.
# LCM_CONTROL_SCENARIO_COMMAND is the command (find_package(lcm_control): the installed `lcm-control scenario`).
function(lcm_control_add_scenario name file)
  cmake_parse_arguments(ARG "" "TIMEOUT" "PACKAGE_PATH;LABELS" ${ARGN})
  if(NOT LCM_CONTROL_SCENARIO_COMMAND)
    message(FATAL_ERROR "lcm_control_add_scenario(${name}): LCM_CONTROL_SCENARIO_COMMAND is not set "
                        "(find_package(lcm_control) sets it)")
  endif()
  get_filename_component(scenario_file "${file}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  if(NOT EXISTS "${scenario_file}")
    message(FATAL_ERROR "lcm_control_add_scenario(${name}): no scenario file ${scenario_file}")
  endif()
  set(package_path)
  foreach(dir IN LISTS ARG_PACKAGE_PATH)
    list(APPEND package_path --package-path "${dir}")
  endforeach()
  add_test(NAME ${name}
           COMMAND ${LCM_CONTROL_SCENARIO_COMMAND} run "${scenario_file}" ${package_path} --skipped-exit 77
                   --junit "${CMAKE_CURRENT_BINARY_DIR}/${name}.junit.xml")
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT ${ARG_TIMEOUT} LABELS "scenario;${ARG_LABELS}")
endfunction()
