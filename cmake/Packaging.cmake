# Install layout and the Debian package. Included last by the top-level
# CMakeLists.txt, after every target exists. The targets install themselves (core/,
# app/, app/gui); this file installs the data, the desktop integration, the udev rules,
# the docs and the CMake package of the core, and configures CPack.
#
#   cmake --install build/release --prefix /opt/palpa     # a plain install
#   cd build/release && cpack -G DEB                      # palpa_VERSION_amd64.deb
#
# Installed tree (prefix /usr for the .deb):
#   bin/palpa, bin/palpa-cli
#   share/palpa/cases/*.json, share/palpa/schema/       found at run time (core io/data_paths)
#   share/applications/palpa.desktop, share/icons/hicolor/scalable/apps/palpa.svg
#   lib/udev/rules.d/70-palpa.rules
#   share/doc/palpa/                                    README, docs/ (links kept)
#   include/palpa/, lib/libpalpa_core.a, lib/cmake/Palpa/   find_package(Palpa) -> Palpa::core
include(CMakePackageConfigHelpers)

set(PALPA_DATA_INSTALL_DIR ${CMAKE_INSTALL_DATADIR}/palpa)
set(PALPA_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Palpa)

# Bundled data: the cases (not the script that makes them), the schema and the reference curves.
install(DIRECTORY data/cases/ DESTINATION ${PALPA_DATA_INSTALL_DIR}/cases FILES_MATCHING PATTERN "*.json")
install(FILES data/schema/palpa-case.schema.json DESTINATION ${PALPA_DATA_INSTALL_DIR}/schema)
# The finite-element reference curves that palpa-cli bench fidelity compares with.
install(DIRECTORY data/reference/ DESTINATION ${PALPA_DATA_INSTALL_DIR}/reference
        FILES_MATCHING PATTERN "*.csv" PATTERN "README.md")

# Desktop menu entry and icon.
install(FILES packaging/palpa.desktop DESTINATION ${CMAKE_INSTALL_DATADIR}/applications)
install(FILES packaging/palpa.svg DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/scalable/apps)

# Device access without root (packaging/README.md). Relative to the prefix: /usr/lib/udev
# for the package, which udev reads on Debian 12 (merged /usr).
install(FILES packaging/udev/70-palpa.rules DESTINATION lib/udev/rules.d)

# Documentation, laid out as in the source tree so the README's and the guides' relative
# links (docs/..., docs/images/...) still work.
install(FILES README.md BENCHMARKS.md LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})
# Debian looks for the licence as /usr/share/doc/PACKAGE/copyright.
install(FILES LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR} RENAME copyright)
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)

# The core for other projects: find_package(Palpa) -> Palpa::core.
install(EXPORT PalpaTargets NAMESPACE Palpa:: DESTINATION ${PALPA_CMAKE_INSTALL_DIR})
configure_package_config_file(packaging/PalpaConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/PalpaConfig.cmake
  INSTALL_DESTINATION ${PALPA_CMAKE_INSTALL_DIR}
  PATH_VARS PALPA_DATA_INSTALL_DIR CMAKE_INSTALL_INCLUDEDIR)
# 0.x: a new minor version may change the API, so only the same minor version is compatible.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/PalpaConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/PalpaConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/PalpaConfigVersion.cmake
  DESTINATION ${PALPA_CMAKE_INSTALL_DIR})

# CPack: one Debian package, palpa_VERSION_ARCH.deb, version from project() above.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME palpa)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "The Palpa project")
# The package's Maintainer field: whoever publishes the package sets it (-D at configure).
set(PALPA_PACKAGE_MAINTAINER "Palpa maintainers <palpa@localhost>" CACHE STRING
    "Maintainer field of the Debian package (Name <email>)")
set(CPACK_PACKAGE_CONTACT "${PALPA_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "palpation trainer on a medial-axis haptic tissue model")
set(CPACK_PACKAGE_DESCRIPTION
  "Palpa trains palpation: trainees press a virtual or haptic-device fingertip into soft
tissue on screen, feel it push back, search it for hidden stiff tumours, mark them and
get scored. Instructors author the cases; every exercise is recorded and can be replayed
and reported. The physics is the medial-axis haptic model of Corso, Chhugani and Okamura.
.
This package holds the application (palpa: trainee, instructor and review windows), the
command-line tools (palpa-cli: validate, fit, exercise, score, batch, bench, devices), the
bundled cases, udev rules for the SpaceMouse and the Novint Falcon, the documentation, and
the headless core library with its CMake package (find_package(Palpa): Palpa::core).")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # palpa_0.1.0_amd64.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Depends from the binaries' shared libraries (dpkg-shlibdeps): Qt, VTK, OpenCV, SQLite,
# hidapi, libusb, the C++ runtime.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# udevadm for the postinst; the headers the core's CMake package needs when a project
# builds against it.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "udev")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS
  "cmake, g++, libeigen3-dev, nlohmann-json3-dev, libfmt-dev, libnanoflann-dev, libsqlite3-dev, zlib1g-dev, desktop-file-utils")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA "${PROJECT_SOURCE_DIR}/packaging/debian/postinst;${PROJECT_SOURCE_DIR}/packaging/debian/postrm")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
