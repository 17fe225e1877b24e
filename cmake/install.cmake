# What `cmake --install` puts beside the rtmot binary (installed by apps/CMakeLists.txt), for a board or
# a package. Included by the top-level CMakeLists.txt after GNUInstallDirs. With the default prefix
# /usr/local this matches scripts/deploy/rtmot.service:
#   bin/rtmot
#   share/rtmot/configs/*.yaml          run configurations (jetson-csi.yaml is the service's)
#   share/doc/rtmot/*.md, README.md     documentation
#   lib/systemd/system/rtmot.service    the service (systemd reads /usr/local/lib/systemd/system)
#   lib/sysusers.d/rtmot.conf           its system user (apply with systemd-sysusers FILE)
# The model is not installed: it is fetched (scripts/fetch_model.sh) and its path set in the config.
include(GNUInstallDirs)

install(DIRECTORY "${PROJECT_SOURCE_DIR}/configs/" DESTINATION "${CMAKE_INSTALL_DATADIR}/rtmot/configs"
        FILES_MATCHING PATTERN "*.yaml" PATTERN "*.yml")
install(DIRECTORY "${PROJECT_SOURCE_DIR}/docs/" DESTINATION "${CMAKE_INSTALL_DOCDIR}" FILES_MATCHING PATTERN "*.md")
install(FILES "${PROJECT_SOURCE_DIR}/README.md" DESTINATION "${CMAKE_INSTALL_DOCDIR}" OPTIONAL)

set(RTMOT_SYSTEMD_UNIT_DIR "lib/systemd/system" CACHE STRING "Where to install rtmot.service, relative to the prefix")
install(FILES "${PROJECT_SOURCE_DIR}/scripts/deploy/rtmot.service" DESTINATION "${RTMOT_SYSTEMD_UNIT_DIR}")
install(FILES "${PROJECT_SOURCE_DIR}/scripts/deploy/rtmot.sysusers.conf" DESTINATION "lib/sysusers.d"
        RENAME rtmot.conf)
