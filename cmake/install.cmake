# What `cmake --install` puts on a board (or into a package), and nothing else. Included by the
# top-level CMakeLists.txt before the targets exist. With --prefix P (default /usr/local):
#   P/bin/rtmot                          RUNPATH $ORIGIN/../lib/rtmot: the tree may move (DESTDIR,
#                                        another prefix) and still finds what it ships
#   P/lib/rtmot/libopencv_*.so.*         the OpenCV it was built with, when that is not the system's
#                                        (the pinned 4.10 of scripts/build_opencv.sh); with Debian's
#                                        OpenCV the board gets it from apt and nothing is copied
#   P/share/rtmot/configs/*.yaml         run configurations (jetson-csi.yaml is the service's)
#   P/share/rtmot/models/*               the SSD model, when it was fetched before the install
#                                        (scripts/fetch_model.sh); configs name it ../models/...
#   P/share/rtmot/web/*                  the pages (index.html, editor.js, app.js, settings.js, listen.html,
#                                        listen.js, style.css; found
#                                        from the binary: outputs/web_server.hpp, docs/web.md)
#   P/share/doc/rtmot/*.md, README.md    the product's documentation (not the study's tables/plots)
#   P/lib/systemd/system/rtmot.service   the service, ExecStart=P/bin/rtmot --config P/share/...
#                                        (written at install time from the prefix actually used)
#   P/lib/sysusers.d/rtmot.conf          its system user (apply with systemd-sysusers FILE)
# Checked by tests/system/installed_tree_runs.sh (ctest -R install), which installs into a DESTDIR.
include(GNUInstallDirs)

set(RTMOT_PRIVATE_LIBDIR "${CMAKE_INSTALL_LIBDIR}/rtmot")
# Every executable created after this line gets it; only rtmot is installed. CMake's default is an
# empty install RUNPATH: the build tree's path to the pinned OpenCV was stripped and the installed
# binary could not start (libopencv_dnn.so.410 not found).
file(RELATIVE_PATH rtmot_bin_to_lib "/${CMAKE_INSTALL_BINDIR}" "/${RTMOT_PRIVATE_LIBDIR}")
set(CMAKE_INSTALL_RPATH "$ORIGIN/${rtmot_bin_to_lib}")

# The OpenCV libraries rtmot loads, resolved from the build-tree binary at install time, copied
# (the real file, plus its soname link) when they live outside the system's library folders.
# Debian's (/usr/lib/...) are left to apt; anything else would be missing on the target.
set(rtmot_ship_opencv [[
  file(GET_RUNTIME_DEPENDENCIES
       EXECUTABLES "$<TARGET_FILE:rtmot>"
       RESOLVED_DEPENDENCIES_VAR rtmot_deps
       UNRESOLVED_DEPENDENCIES_VAR rtmot_unresolved
       PRE_INCLUDE_REGEXES "libopencv_"
       PRE_EXCLUDE_REGEXES ".*"
       DIRECTORIES "$<TARGET_FILE_DIR:opencv_core>")
  if(rtmot_unresolved)
    message(FATAL_ERROR "rtmot: cannot find the OpenCV libraries it links: ${rtmot_unresolved}")
  endif()
  foreach(dep IN LISTS rtmot_deps)
    if(NOT dep MATCHES "^/(usr/)?lib(32|64)?/")
      file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/@RTMOT_PRIVATE_LIBDIR@" TYPE SHARED_LIBRARY
           FOLLOW_SYMLINK_CHAIN FILES "${dep}")
    endif()
  endforeach()
]])
string(CONFIGURE "${rtmot_ship_opencv}" rtmot_ship_opencv @ONLY)
install(CODE "${rtmot_ship_opencv}")

install(DIRECTORY "${PROJECT_SOURCE_DIR}/configs/" DESTINATION "${CMAKE_INSTALL_DATADIR}/rtmot/configs"
        FILES_MATCHING PATTERN "*.yaml" PATTERN "*.yml")
install(DIRECTORY "${PROJECT_SOURCE_DIR}/web/" DESTINATION "${CMAKE_INSTALL_DATADIR}/rtmot/web"
        FILES_MATCHING PATTERN "*.html" PATTERN "*.js" PATTERN "*.css")
# The model: absent until scripts/fetch_model.sh ran (then a config names it with --model or an
# absolute path, as before).
install(DIRECTORY "${PROJECT_SOURCE_DIR}/models/" DESTINATION "${CMAKE_INSTALL_DATADIR}/rtmot/models" OPTIONAL
        FILES_MATCHING PATTERN "*.onnx" PATTERN "*.anchors.csv" PATTERN "*.sha256")
# What an operator of a board reads; the research (study, scoring, results) stays in the source tree.
install(FILES "${PROJECT_SOURCE_DIR}/README.md" DESTINATION "${CMAKE_INSTALL_DOCDIR}" OPTIONAL)
foreach(doc architecture config cross-and-deploy exit-codes gpu message-format model reliability sources web)
  install(FILES "${PROJECT_SOURCE_DIR}/docs/${doc}.md" DESTINATION "${CMAKE_INSTALL_DOCDIR}")
endforeach()

# The unit names absolute paths, so it is written when the prefix is known: at install time
# (`cmake --install build --prefix /usr` gives ExecStart=/usr/bin/rtmot ... /usr/share/...).
set(RTMOT_SYSTEMD_UNIT_DIR "lib/systemd/system" CACHE STRING "Where to install rtmot.service, relative to the prefix")
set(rtmot_write_unit [[
  set(RTMOT_BINDIR "@CMAKE_INSTALL_BINDIR@")
  set(RTMOT_DATADIR "@CMAKE_INSTALL_DATADIR@")
  set(RTMOT_DOCDIR "@CMAKE_INSTALL_DOCDIR@")
  foreach(dir RTMOT_BINDIR RTMOT_DATADIR RTMOT_DOCDIR)
    if(NOT IS_ABSOLUTE "${${dir}}")
      set(${dir} "${CMAKE_INSTALL_PREFIX}/${${dir}}")
    endif()
  endforeach()
  configure_file("@PROJECT_SOURCE_DIR@/scripts/deploy/rtmot.service.in"
                 "@PROJECT_BINARY_DIR@/rtmot.service" @ONLY)
  file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/@RTMOT_SYSTEMD_UNIT_DIR@" TYPE FILE
       FILES "@PROJECT_BINARY_DIR@/rtmot.service")
]])
string(CONFIGURE "${rtmot_write_unit}" rtmot_write_unit @ONLY)
install(CODE "${rtmot_write_unit}")
install(FILES "${PROJECT_SOURCE_DIR}/scripts/deploy/rtmot.sysusers.conf" DESTINATION "lib/sysusers.d"
        RENAME rtmot.conf)
