# link_graph_check: fails naming the target and the library when a link closure (written
# by tests/structure/CMakeLists.txt at configure time) breaks a rule below.
#   cmake -DCLOSURE_DIR=<build>/tests/structure/link_closure -P check_link_graph.cmake

# The flight software: mission layer, planner, SAMPC (and its NLopt reference solver).
set(flight cover_mission cover_planner cover_sampc cover_uav_loop cover_wire_mission nlopt)
# The simulator and what is built on it.
set(simulator cover_sim cover_closed_loop cover_sim_fc cover_sim_mocap)

cmake_policy(SET CMP0057 NEW)  # if(IN_LIST) in script mode

# target -> what it must not link
set(forbid_cover_task_file ${flight} ${simulator})
set(forbid_cover_task_store ${flight} ${simulator})
set(forbid_cover_task_dispatch ${flight} ${simulator})
set(forbid_cover-task-manager ${flight} ${simulator})
set(forbid_cover_wire ${flight} ${simulator} cover_model cover_imu_filter cover_speed_estimator
                      cover_task_file cover_config cover_clock)
# A UGV's software needs nothing of the UAV's (its model's dynamics included).
set(forbid_cover_ugv_imu_source ${flight} ${simulator} cover_model)
set(forbid_cover-ugv-agent ${flight} ${simulator} cover_model)
# The parameter structs' libraries, without DDS: cover-params reads every one of them.
set(dds cover_dds cover_time_sync_dds fastrtps ddsc)
set(forbid_cover_sim_process_params ${dds})
set(forbid_cover_ugv_agent_params ${dds})
set(forbid_cover-params ${dds})
# target -> the only libraries it may link: the fleet's vocabulary sits under every module.
set(only_cover_vocabulary Eigen3::Eigen)
# target -> what it must link: the walk sees transitive and private (LINK_ONLY) libraries,
# so an empty closure cannot pass the rules above.
set(require_cover_vocabulary Eigen3::Eigen)
set(require_cover-uav-agent cover_mission cover_sampc nlopt)
set(require_cover-sim cover_sim cover_vocabulary)
set(require_cover-ugv-agent cover_ugv_imu_source cover_vocabulary)
set(require_cover-task-manager cover_task_store cover_task_file)
set(require_cover-params cover_sampc cover_sim_process_params cover_ugv_agent_params)

set(targets cover_vocabulary cover_task_file cover_task_store cover_task_dispatch cover-task-manager cover_wire
            cover_ugv_imu_source cover-ugv-agent cover-uav-agent cover-sim
            cover_sim_process_params cover_ugv_agent_params cover-params)

# Whether `library` (a target name, or nlopt in any spelling: NLopt::nlopt, libnlopt.so)
# is among `items`.
function(has_library items library out)
  set(found FALSE)
  foreach(item IN LISTS items)
    if(library STREQUAL "nlopt")
      string(TOLOWER "${item}" lower)
      if(lower MATCHES "nlopt")
        set(found TRUE)
      endif()
    elseif(item STREQUAL library OR item MATCHES "(^|[/ ])lib${library}\\.(a|so)")
      set(found TRUE)
    endif()
  endforeach()
  set(${out} ${found} PARENT_SCOPE)
endfunction()

set(errors "")
foreach(target IN LISTS targets)
  set(file ${CLOSURE_DIR}/${target}.txt)
  if(NOT EXISTS ${file})
    string(APPEND errors "  ${target}: no link closure at ${file} (re-run cmake)\n")
    continue()
  endif()
  file(STRINGS ${file} closure)
  # The real link line too, where the generator writes one (Makefiles: link.txt).
  set(link_line "")
  if(EXISTS ${CLOSURE_DIR}/${target}.link_txt_path)
    file(READ ${CLOSURE_DIR}/${target}.link_txt_path link_txt)
    if(EXISTS "${link_txt}")
      file(READ "${link_txt}" link_line)
      string(REPLACE " " ";" link_line "${link_line}")
    endif()
  endif()
  foreach(library IN LISTS forbid_${target})
    has_library("${closure}" ${library} in_closure)
    has_library("${link_line}" ${library} in_line)
    if(in_closure OR in_line)
      string(APPEND errors "  ${target} links ${library}\n")
    endif()
  endforeach()
  if(DEFINED only_${target})
    foreach(item IN LISTS closure)
      if(NOT item IN_LIST only_${target})
        string(APPEND errors "  ${target} links ${item}; it may link only ${only_${target}}\n")
      endif()
    endforeach()
  endif()
  foreach(library IN LISTS require_${target})
    has_library("${closure}" ${library} in_closure)
    if(NOT in_closure)
      string(APPEND errors "  ${target} does not link ${library}: the closure walk is broken\n")
    endif()
    if(link_line)
      has_library("${link_line}" ${library} in_line)
      if(NOT in_line)
        string(APPEND errors "  ${target}'s link.txt does not name ${library}\n")
      endif()
    endif()
  endforeach()
endforeach()

if(errors)
  message(FATAL_ERROR "link graph rules broken:\n${errors}")
endif()
list(LENGTH targets count)
message(STATUS "link graph: ${count} targets follow the rules")
