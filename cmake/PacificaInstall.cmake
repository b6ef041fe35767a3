# Install rules and the package config, so an outside project can find_package(Pacifica).
include(GNUInstallDirs)
