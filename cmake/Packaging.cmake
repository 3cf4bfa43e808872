# Debian packages with CPack (board/package.sh runs it on a built tree):
#   candela       the kiosk: candela, candela-record, scenes, stories, built-in models,
#                 the systemd unit, its user (sysusers.d), the GPIO udev rule
#                 and the conffile /etc/candela/candela.toml
#   candela-tool  the offline tools (Eigen, FFTW, libav): kept out of the
#                 kiosk package so a board does not pull them in
# Depends come from dpkg-shlibdeps. Paths are Debian 12's (/lib/systemd,
# /lib/udev: bookworm's debhelper puts them there too).
set(pkg ${CMAKE_SOURCE_DIR}/board/package)

install(DIRECTORY ${CMAKE_SOURCE_DIR}/firmware/scenes/ DESTINATION share/candela/scenes
        COMPONENT candela FILES_MATCHING PATTERN "*.toml")
# The example stories (also built in: story = "builtin:NAME"), as files to copy and edit.
install(DIRECTORY ${CMAKE_SOURCE_DIR}/firmware/stories/ DESTINATION share/candela/stories
        COMPONENT candela FILES_MATCHING PATTERN "*.toml")
install(FILES ${CMAKE_SOURCE_DIR}/firmware/models/default.cmodel
              ${CMAKE_SOURCE_DIR}/firmware/models/fire.cmodel
        DESTINATION share/candela/models COMPONENT candela)
install(FILES ${CMAKE_SOURCE_DIR}/board/systemd/candela.service
        DESTINATION /lib/systemd/system COMPONENT candela)
install(FILES ${pkg}/sysusers.conf DESTINATION lib/sysusers.d RENAME candela.conf COMPONENT candela)
install(FILES ${pkg}/60-candela-gpio.rules DESTINATION /lib/udev/rules.d COMPONENT candela)
install(FILES ${pkg}/candela.toml DESTINATION /etc/candela COMPONENT candela)

# Debian wants a copyright file and a gzip -9n changelog per package.
set(changelog_gz ${CMAKE_BINARY_DIR}/package/changelog.gz)
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/package)
execute_process(COMMAND gzip -9nc ${pkg}/changelog OUTPUT_FILE ${changelog_gz} COMMAND_ERROR_IS_FATAL ANY)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${pkg}/changelog)
foreach(comp candela candela-tool)
  install(FILES ${pkg}/copyright ${changelog_gz} DESTINATION share/doc/${comp} COMPONENT ${comp})
endforeach()
install(FILES ${CMAKE_SOURCE_DIR}/README.md DESTINATION share/doc/candela COMPONENT candela)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME candela)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_PACKAGE_CONTACT "Candela maintainers <maintainers@users.noreply.h-seed-3f212c05.example>")
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL candela candela-tool)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "https://example.invalid/candela")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_DEBIAN_CANDELA_PACKAGE_NAME candela)
set(CPACK_DEBIAN_CANDELA-TOOL_PACKAGE_NAME candela-tool)
string(CONCAT CPACK_DEBIAN_CANDELA_DESCRIPTION
    "living candle and fireplace kiosk for a screen\n"
    "Candela draws candles and fireplaces with OpenGL ES on DRM/KMS (a\n"
    "Raspberry Pi 4/5 and a screen), in a desktop window or headless. This\n"
    "package boots a board straight into the scene named in\n"
    "/etc/candela/candela.toml, as the unprivileged user candela, and reads\n"
    "buttons, sensors and cameras; candela-record records flame footage.")
set(CPACK_COMPONENT_CANDELA_DESCRIPTION "${CPACK_DEBIAN_CANDELA_DESCRIPTION}")
set(CPACK_DEBIAN_CANDELA-TOOL_DESCRIPTION "${CPACK_COMPONENT_CANDELA-TOOL_DESCRIPTION}")
string(CONCAT CPACK_COMPONENT_CANDELA-TOOL_DESCRIPTION
    "offline tools for the Candela flame kiosk\n"
    "candela-tool builds eigen-flame models from footage or simulation,\n"
    "makes noise tables and measures how real a rendered flame looks. Not\n"
    "needed on the kiosk itself.")
# Maintainer scripts use adduser (where systemd-sysusers is missing) and
# deb-systemd-helper; shlibdeps adds the libraries.
set(CPACK_DEBIAN_CANDELA_PACKAGE_DEPENDS "adduser, init-system-helpers (>= 1.52)")
# Not needed to show a flame, but what a user expects where they are: ffmpeg
# for --out FILE.mp4, libcec6 to switch a TV by HDMI-CEC (dlopened).
set(CPACK_DEBIAN_CANDELA_PACKAGE_RECOMMENDS "ffmpeg, libcec6")
set(CPACK_DEBIAN_CANDELA-TOOL_PACKAGE_RECOMMENDS "ffmpeg")
set(CPACK_DEBIAN_CANDELA_PACKAGE_CONTROL_EXTRA
    ${pkg}/conffiles ${pkg}/postinst ${pkg}/prerm ${pkg}/postrm)
include(CPack)
