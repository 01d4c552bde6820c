# The Debian package (bash scripts/package.sh): formsim_<version>_amd64.deb made by CPack from the
# install rules above, with the Python module inside. Library dependencies are computed by
# dpkg-shlibdeps; what is loaded at run time rather than linked is named here.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME formsim)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
# Install with DESTDIR and the real prefix, so that install rules see /usr (the Python module
# goes to /usr/lib/python3/dist-packages there).
set(CPACK_SET_DESTDIR ON)
set(CPACK_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_PACKAGE_CONTACT "The formsim developers <formsim@users.noreply.github.com>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "simulator for multi-robot formation control and navigation")
# The long description (the synopsis is CPACK_PACKAGE_DESCRIPTION_SUMMARY); CPack indents each
# line and turns the empty line into " .".
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
    "formsim makes multi-robot formation control and mobile-robot navigation
visible, tunable and reproducible. Box2D bodies model the robots; controllers
and estimators from four papers drive them (a cascade leader-follower
formation with a UKF per link, a Mecanum AGV with Kalman fusion, an
inspection robot with fuzzy control, fused velocity control).

An interactive window tunes gains and noise while a run goes on, with
lessons for teaching; headless, the same pictures are written as frames,
video and paper-style figures. Sweeps and tuning search gains
systematically. Includes the Python module formsim.")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# Not linked but needed: the fonts every label is drawn with, and for the Python module its
# interpreter (built for 3.11's ABI) and numpy.
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "fonts-dejavu-core, python3 (>= 3.11), python3 (<< 3.12), python3-numpy")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "ffmpeg, python3-pandas")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "xvfb, python3-distributed")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "")
set(CPACK_OUTPUT_FILE_PREFIX ${PROJECT_BINARY_DIR}/package)
include(CPack)
