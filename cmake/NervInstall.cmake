# `cmake --install build [--prefix P]`: what a vehicle computer needs to run nerv
# (README "Installing on a vehicle computer"):
#   bin/                      the four services, nerv_up, nerv_source and the log tools
#   share/nerv/config/        pipeline.yaml, the camera presets, the synthetic scenes
#   share/nerv/lcmtypes/      the message definitions, for clients in other languages
#   share/nerv/nerv_types.jar the Java types (lcm-spy, Java clients), when built
#   etc/nerv/pipeline.yaml    the config the systemd unit reads; installed only when absent
#   lib/systemd/system/nerv.service, lib/sysctl.d/60-nerv-lcm.conf
# nerv_up finds the services next to itself, so bin/ must hold them all.
include(GNUInstallDirs)

set(NERV_INSTALL_TARGETS
    nerv_stereo_matcher_service nerv_stixel_service nerv_snv_extrinsic_service nerv_validator_service
    nerv_up nerv_source nerv_export nerv_diff nerv_render nerv_report nerv_eval_detections
    nerv_eval_disparity nerv_unrectify nerv_misalign nerv_synth_cli)
# `cmake --build B --target nerv_installable`: only what is installed (tools/nerv package
# --march builds that, not the tests and benches).
add_custom_target(nerv_installable)
foreach(target ${NERV_INSTALL_TARGETS})
  if(TARGET ${target})
    install(TARGETS ${target} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    add_dependencies(nerv_installable ${target})
  endif()
endforeach()
if(TARGET nerv_types_jar)
  add_dependencies(nerv_installable nerv_types_jar)
endif()

set(NERV_SHARE ${CMAKE_INSTALL_DATADIR}/nerv)
install(FILES ${CMAKE_SOURCE_DIR}/config/pipeline.yaml DESTINATION ${NERV_SHARE}/config)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/config/cameras ${CMAKE_SOURCE_DIR}/config/scenes
        DESTINATION ${NERV_SHARE}/config)
install(FILES ${NERV_LCM_TYPES} DESTINATION ${NERV_SHARE}/lcmtypes)
if(NERV_TYPES_JAR)
  install(FILES ${NERV_TYPES_JAR} DESTINATION ${NERV_SHARE})
endif()

# The unit and the config it names refer to the installed paths (the prefix given at install).
# file(INSTALL) puts DESTDIR (a staged install, tools/package/make_deb.sh) before an absolute
# destination itself; EXISTS does not.
install(CODE "
  set(prefix \"\${CMAKE_INSTALL_PREFIX}\")
  set(NERV_BINDIR \"\${prefix}/${CMAKE_INSTALL_BINDIR}\")
  if(IS_ABSOLUTE \"${CMAKE_INSTALL_SYSCONFDIR}\")
    set(etc \"${CMAKE_INSTALL_SYSCONFDIR}\")
  else()
    set(etc \"\${prefix}/${CMAKE_INSTALL_SYSCONFDIR}\")
  endif()
  set(NERV_CONFIG \"\${etc}/nerv/pipeline.yaml\")
  configure_file(\"${CMAKE_SOURCE_DIR}/deploy/nerv.service.in\" \"${CMAKE_BINARY_DIR}/deploy/nerv.service\" @ONLY)
  file(INSTALL \"${CMAKE_BINARY_DIR}/deploy/nerv.service\"
       DESTINATION \"\${prefix}/lib/systemd/system\")
  file(INSTALL \"${CMAKE_SOURCE_DIR}/deploy/60-nerv-lcm.conf\"
       DESTINATION \"\${prefix}/lib/sysctl.d\")
  if(EXISTS \"\$ENV{DESTDIR}\${NERV_CONFIG}\")
    message(STATUS \"Kept: \$ENV{DESTDIR}\${NERV_CONFIG} (already there)\")
  else()
    file(INSTALL \"${CMAKE_SOURCE_DIR}/config/pipeline.yaml\" DESTINATION \"\${etc}/nerv\")
  endif()
")
