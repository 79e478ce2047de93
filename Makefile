# armctl — the README's commands. Each target does its own setup on a fresh Debian 12.
#   make demo   build an optimised armctl only (build/demo) and drive the simulated arms
#   make test   build with ASan+UBSan and run the whole test suite (CTest)
#   make bench  build optimised and run the benchmarks (BENCH lines)
#   make fuzz   run the libFuzzer targets for longer (FUZZ_SECONDS=60)
#   make firmware / make flash PORT=/dev/ttyUSB0 JOINT=3
#   make flash-controller PORT=/dev/ttyACM0   the Mega arm controller (docs/mega-controller.md)

# Debian packages and why they are here: see README.md "Dependencies".
DEB_PACKAGES := build-essential cmake ninja-build pkg-config \
  libgtest-dev libgmock-dev libbenchmark-dev \
  libcli11-dev libfmt-dev nlohmann-json3-dev \
  libhidapi-dev libgpiod-dev \
  gcc-avr avr-libc binutils-avr avrdude simavr libsimavr-dev libelf-dev \
  clang libclang-rt-14-dev ccache lld \
  liburdfdom-dev libtinyxml-dev liborocos-kdl-dev libkdl-parser-dev libeigen3-dev libfcl-dev libompl-dev \
  pybind11-dev python3-dev python3-pytest python3-numpy \
  libcpp-httplib-dev libevdev-dev tmux \
  libroscpp-dev libactionlib-dev libactionlib-msgs-dev libsensor-msgs-dev libtrajectory-msgs-dev \
  libgeometry-msgs-dev libdiagnostic-msgs-dev libstd-msgs-dev libstd-srvs-dev libtf2-ros-dev \
  python3-genmsg python3-gencpp python3-genpy python3-rosmaster ros-robot-state-publisher python3-roslaunch \
  python3-rospy python3-actionlib python3-rosservice python3-sensor-msgs python3-trajectory-msgs

# What `make demo` installs: only what configuring and building the armctl CLI (Release)
# needs, and python3 for the demo's picture (scripts/demo_picture.py). Not the test, benchmark,
# firmware, Python-module or ROS packages above: the demo builds none of that.
DEMO_PACKAGES := build-essential cmake ninja-build pkg-config lld \
  libcli11-dev libfmt-dev nlohmann-json3-dev libhidapi-dev libgpiod-dev \
  libeigen3-dev liburdfdom-dev libtinyxml-dev libfcl-dev libompl-dev libcpp-httplib-dev libevdev-dev python3

SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
JOBS ?= 2
BUILD := build
BENCH_BUILD := build/bench-release
RELEASE_BUILD := build/release
DEMO_BUILD := build/demo
PREFIX ?= /usr/local
UDEV_RULES_DIR ?= /etc/udev/rules.d
# The test and benchmark builds need the firmware and its HIL tests (avr-gcc, simavr): ON
# makes a missing tool an error instead of a skipped part (cmake/Options.cmake).
WITH_FIRMWARE := -DARMCTL_FIRMWARE=ON -DARMCTL_HIL=ON
# The Python module (pybind11; docs/python.md): ON, so that a missing package fails the build.
WITH_PYTHON := -DARMCTL_PYTHON=ON
# The benchmarks build without it: the module makes every library position-independent code.
# The dashboard's browser tests (tests/browser): ON, so that a missing node or chromium fails.
WITH_BROWSER := -DARMCTL_BROWSER_TESTS=ON
# The ROS 1 node (docs/ros.md): ON, so that a missing ROS package fails the build.
WITH_ROS := -DARMCTL_ROS=ON
FUZZ_BUILD := build/fuzz
FUZZ_SECONDS ?= 60
# make test runs each fuzz target on a fixed number of inputs from its seeds with a fixed seed:
# the same inputs on every machine (scripts/fuzz.sh), two targets at a time; the slowest
# (fuzz_arm_file, fuzz_arm_config: whole arm files under ASan) take about 90 s each.
TEST_FUZZ_RUNS ?= 5000

.PHONY: all deps deb-deps demo-deps web-deps configure build test demo python bench fuzz firmware flash flash-controller install uninstall clean format

all: build

# Install only what is missing, so repeated runs cost nothing and need no network: the Debian
# packages, then the dashboard's npm packages (armctl embeds them, so every build needs them).
deps: deb-deps web/node_modules

# $(call missing_packages,LIST): the shell words that print the packages of LIST not installed.
missing_packages = for p in $(1); do \
	    dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; done

deb-deps:
	@missing=$$($(call missing_packages,$(DEB_PACKAGES))); \
	if [ -n "$$missing" ]; then \
	  echo "Installing Debian packages: $$missing"; \
	  $(SUDO) apt-get update && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y --no-install-recommends $$missing; \
	fi
	@# The dashboard (web/) and its browser tests: node + npm and chromium, from Debian when the
	@# commands are missing (a machine may have another node that brings its own npm).
	@missing=$$(command -v node >/dev/null || echo nodejs; command -v npm >/dev/null || echo npm; \
	  command -v chromium >/dev/null || echo chromium); \
	if [ -n "$$missing" ]; then \
	  echo "Installing Debian packages: $$missing"; \
	  $(SUDO) apt-get update && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y --no-install-recommends $$missing; \
	fi

# The dashboard's npm packages, pinned in web/package-lock.json: three and urdf-loader (the
# page's 3D view, embedded into armctl), playwright-core (the browser tests). Installed again
# only when the lock file is newer than web/node_modules; before CMake configures, which
# embeds web/vendor.txt's files (cmake/WebAssets.cmake) and finds playwright-core for the tests.
web-deps: web/node_modules

# demo-deps: DEMO_PACKAGES, and node + npm when the commands are missing (armctl embeds the
# dashboard's npm packages, so configuring it needs web/node_modules); one apt-get run.
demo-deps:
	@missing=$$($(call missing_packages,$(DEMO_PACKAGES)); \
	  command -v node >/dev/null || echo nodejs; command -v npm >/dev/null || echo npm); \
	if [ -n "$$missing" ]; then \
	  echo "Installing Debian packages: $$missing"; \
	  $(SUDO) apt-get update && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y --no-install-recommends $$missing; \
	fi

# NODE_SETUP: what installs node and npm first (make demo passes demo-deps).
NODE_SETUP ?= deb-deps
web/node_modules: web/package-lock.json | $(NODE_SETUP)
	cd web && npm ci --no-audit --no-fund
	touch $@

$(BUILD)/build.ninja: | deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DARMCTL_SANITIZE=ON $(WITH_FIRMWARE) $(WITH_PYTHON) $(WITH_BROWSER) $(WITH_ROS)

configure: deps $(BUILD)/build.ninja

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# A failed test runs once more, and the run fails only if it fails again: the tests that
# drive the simulators in real time (the dashboard, the ROS node, the Python scripts, the
# browser) can miss a deadline on a machine loaded by other jobs. The first failure's output
# stays in the log; the deterministic tests fail twice just the same.
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 600 -LE long --repeat until-pass:2
	$(MAKE) --no-print-directory fuzz FUZZ_SEED=1 FUZZ_RUNS=$(TEST_FUZZ_RUNS)

# The demo builds only what it runs: an optimised armctl in its own tree, no tests, no
# sanitizers (the test build is 369 targets; this is one), then drives the simulated arms and
# writes build/demo/demo.svg. How long each step takes, measured: README.md "Quick start".
demo:
	@echo "[demo] packages: installing what is missing of: $(DEMO_PACKAGES) (+ nodejs npm)"
	@$(MAKE) --no-print-directory demo-deps
	@$(MAKE) --no-print-directory web/node_modules NODE_SETUP=demo-deps
	@echo "[demo] configuring $(DEMO_BUILD) (Release, the armctl CLI only)"
	@mkdir -p $(DEMO_BUILD)
	cmake -S . -B $(DEMO_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DARMCTL_SANITIZE=OFF \
	  -DARMCTL_TESTS=OFF -DARMCTL_BENCH=OFF -DARMCTL_FIRMWARE=OFF -DARMCTL_HIL=OFF -DARMCTL_PYTHON=OFF \
	  -DARMCTL_ROS=OFF -DARMCTL_QUICK_BUILD=ON > $(DEMO_BUILD)/configure.log || { cat $(DEMO_BUILD)/configure.log; exit 1; }
	@echo "[demo] building $(DEMO_BUILD)/armctl on $(JOBS) cores (a first build takes a few minutes; then seconds)"
	cmake --build $(DEMO_BUILD) -j $(JOBS) --target armctl
	./scripts/demo.sh $(DEMO_BUILD)/armctl

bench: deps
	cmake -S . -B $(BENCH_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DARMCTL_SANITIZE=OFF $(WITH_FIRMWARE) -DARMCTL_PYTHON=OFF $(WITH_ROS)
	cmake --build $(BENCH_BUILD) -j $(JOBS)
	./scripts/bench.sh $(BENCH_BUILD)

fuzz: deps
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DARMCTL_FUZZ=ON
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target armctl_fuzz_all
	JOBS=$(JOBS) ./scripts/fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_SEED) $(FUZZ_RUNS)

# Joint controller firmware into build/firmware/ (docs/firmware.md). flash programs one
# board through its bootloader and sets its joint number in EEPROM:
#   make flash PORT=/dev/ttyUSB0 JOINT=3 [BOOTLOADER_BAUD=57600 for old Nano bootloaders]
#              [JOINT_BAUD=115200 for a 115200 baud joint bus]
firmware: deps
	$(MAKE) -C firmware BUILD_DIR=$(CURDIR)/$(BUILD)/firmware

flash: deps
	$(MAKE) -C firmware flash BUILD_DIR=$(CURDIR)/$(BUILD)/firmware

# The Mega 2560 as the SCARA's arm controller (docs/mega-controller.md). PORT is the Mega's
# USB serial port; RC_BAUD=115200 / JOINT_BAUD=115200 select the faster links.
flash-controller: deps
	$(MAKE) -C firmware flash-controller BUILD_DIR=$(CURDIR)/$(BUILD)/firmware PORT=$(or $(PORT),/dev/ttyACM0)

# A Release build (no sanitizers, no tests, no firmware: the SDK and CLI need neither avr-gcc
# nor simavr) installed into $(PREFIX): bin/armctl, the static libraries, their headers
# (include/armctl/), the CMake package (lib/cmake/armctl: find_package(armctl)) and the
# default configs (share/armctl), the Python package (lib/python3.N/dist-packages/armctl, where
# Debian's python3 finds it), the ROS package (bin/armctl_ros, share/armctl: package.xml,
# launch/, rviz/; docs/ros.md); then the udev rule for the xArm's USB HID board.
install: deps
	cmake -S . -B $(RELEASE_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DARMCTL_SANITIZE=OFF \
	  -DARMCTL_TESTS=OFF -DARMCTL_BENCH=OFF -DARMCTL_FIRMWARE=OFF -DARMCTL_HIL=OFF $(WITH_PYTHON) $(WITH_ROS) \
	  -DCMAKE_INSTALL_PREFIX=$(PREFIX)
	cmake --build $(RELEASE_BUILD) -j $(JOBS)
	$(SUDO) cmake --install $(RELEASE_BUILD)
	$(SUDO) install -d $(UDEV_RULES_DIR)
	$(SUDO) install -m 0644 udev/50-armctl.rules $(UDEV_RULES_DIR)/50-armctl.rules
	-$(SUDO) udevadm control --reload-rules && $(SUDO) udevadm trigger

# The Python module, optimised and without sanitizers (the test build's module needs the ASan
# runtime preloaded into python3): then `PYTHONPATH=build/python-release/python python3`.
PYTHON_PACKAGES := pybind11-dev python3-dev python3-numpy
PYTHON_BUILD := build/python-release
python:
	@$(MAKE) --no-print-directory demo-deps DEMO_PACKAGES="$(DEMO_PACKAGES) $(PYTHON_PACKAGES)"
	@$(MAKE) --no-print-directory web/node_modules NODE_SETUP=demo-deps
	cmake -S . -B $(PYTHON_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DARMCTL_SANITIZE=OFF \
	  -DARMCTL_TESTS=OFF -DARMCTL_BENCH=OFF -DARMCTL_FIRMWARE=OFF -DARMCTL_HIL=OFF -DARMCTL_PYTHON=ON \
	  -DARMCTL_ROS=OFF -DARMCTL_QUICK_BUILD=ON > /dev/null
	cmake --build $(PYTHON_BUILD) -j $(JOBS) --target armctl_python
	@echo "python: PYTHONPATH=$(PYTHON_BUILD)/python python3"

# Removes what `make install` installed from this tree (CMake's install_manifest.txt lists
# every file) and the udev rule.
uninstall:
	@test -f $(RELEASE_BUILD)/install_manifest.txt || { \
	  echo "make uninstall: $(RELEASE_BUILD)/install_manifest.txt is missing: 'make install' from this tree writes it"; exit 1; }
	xargs -d '\n' $(SUDO) rm -f -- < $(RELEASE_BUILD)/install_manifest.txt
	$(SUDO) rm -f $(UDEV_RULES_DIR)/50-armctl.rules
	-$(SUDO) udevadm control --reload-rules

format:
	find src tests bench fuzz firmware -name '*.[ch]pp' -o -name '*.[ch]' | xargs clang-format -i

clean:
	rm -rf $(BUILD)
