# The fuzz targets: <name>_fuzz.cpp each, the libraries it links, and for a YAML loader the
# shipped files its corpus is seeded from (globs under the source tree). A CDR target writes
# its own seeds (cdr_fuzz.h). Read by the clang fuzz build (CMakeLists.txt here) and by the
# main build's ctest entries (fuzz_tests.cmake).

set(STICKREP_FUZZ_YAML_TARGETS
  map floor_plan error_model study_config robot_config system_config qos_catalog launch_graph
  executive_config locomotion_config localizer_config virtual_robot_config landmark_config)
set(STICKREP_FUZZ_CDR_TARGETS
  sensors_cdr base_cdr perception_cdr localization_cdr mission_cdr system_cdr)

set(fuzz_map_deps stickrep_map)
set(fuzz_map_seeds maps/*.yaml test/maps/*.yaml)
set(fuzz_floor_plan_deps stickrep_map_tool)
set(fuzz_floor_plan_seeds maps/sources/*.floor.yaml)
set(fuzz_error_model_deps stickrep_recovery)
set(fuzz_error_model_seeds configs/error_model_*.yaml)
set(fuzz_study_config_deps stickrep_recovery)
set(fuzz_study_config_seeds configs/study.yaml)
set(fuzz_robot_config_deps stickrep_sensing)
set(fuzz_robot_config_seeds configs/robot.yaml)
set(fuzz_system_config_deps stickrep_runtime_config)
set(fuzz_system_config_seeds configs/system.yaml)
set(fuzz_qos_catalog_deps stickrep_runtime_config)
set(fuzz_qos_catalog_seeds configs/qos.yaml)
set(fuzz_launch_graph_deps stickrep_launch)
set(fuzz_launch_graph_seeds deploy/*.launch.yaml)
set(fuzz_executive_config_deps stickrep_executive)
set(fuzz_executive_config_seeds configs/executive.yaml deploy/configs/executive_*.yaml)
set(fuzz_locomotion_config_deps stickrep_locomotion)
set(fuzz_locomotion_config_seeds configs/locomotion.yaml)
set(fuzz_localizer_config_deps stickrep_localizer)
set(fuzz_localizer_config_seeds configs/localizer.yaml)
set(fuzz_virtual_robot_config_deps stickrep_virtual_robot)
set(fuzz_virtual_robot_config_seeds configs/virtual_robot.yaml deploy/configs/virtual_robot_*.yaml)
set(fuzz_landmark_config_deps stickrep_landmark)
set(fuzz_landmark_config_seeds configs/landmark.yaml)

set(fuzz_sensors_cdr_deps stickrep_convert stickrep_camera)
set(fuzz_base_cdr_deps stickrep_convert)
set(fuzz_perception_cdr_deps stickrep_convert)
set(fuzz_localization_cdr_deps stickrep_convert stickrep_map_msg)
set(fuzz_mission_cdr_deps stickrep_convert)
set(fuzz_system_cdr_deps stickrep_convert)
