#!/usr/bin/env bash
# What the product's CMake requires, and which Debian packages provide it: the GPU machine's package
# set (scripts/gpu_prepare.sh) is DERIVED here from the CMakeLists, never kept as a second list.
#
#   scripts/gpu_deps.sh requirements [SOURCE_DIR]
#       every find_package / pkg_check_modules / pkg_search_module / find_path / find_library in the
#       CMakeLists and *.cmake files of SOURCE_DIR (default: this checkout), one per line:
#       KIND<TAB>NAME<TAB>FILE:LINE<TAB>VARIABLE. Needs python3 only (runs on the GPU machine too).
#   scripts/gpu_deps.sh resolve BUILD_DIR [SOURCE_DIR]
#       each requirement resolved through BUILD_DIR's CMakeCache.txt (a configure of this checkout on
#       Debian 12) to the file CMake found and the Debian package that owns it (dpkg -S):
#       KIND<TAB>NAME<TAB>FILE:LINE<TAB>PACKAGES. Exits 1 naming every requirement it cannot resolve.
#   scripts/gpu_deps.sh packages BUILD_DIR
#       the packages to unpack on the GPU machine: the resolved ones, the packages owning the include
#       folders their pkg-config modules name, and the ELF closure (DT_NEEDED) of every library they
#       link, without the C/C++ runtime that every machine with a compiler has.
#   scripts/gpu_deps.sh check BUILD_DIR [SOURCE_DIR]
#       the CI check (ctest gpu_deps_cover_cmake): resolve succeeds for every requirement.
#
# Provided on the GPU machine, not by Debian packages: OpenCV (scripts/build_opencv.sh builds it),
# Threads (the compiler), PkgConfig (the pkg-config program), CUDA.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
provided_re='^(OpenCV|Threads|PkgConfig|CUDA|CUDAToolkit)$'
# The C/C++ runtime of any Linux machine with a compiler: never unpacked there (a foreign libc on the
# library path breaks every program).
runtime_re='^(libc6|libc6-dev|libgcc-s1|libstdc\+\+6|libc-dev-bin|linux-libc-dev|libcrypt1|gcc-[0-9]+-base)(:.*)?$'

die() {
  echo "gpu_deps: $*" >&2
  exit 1
}

requirements() {
  local source_dir="${1:-$repo}"
  python3 - "$source_dir" <<'PY'
import os, re, sys
root = sys.argv[1]
call = re.compile(r'\b(find_package|pkg_check_modules|pkg_search_module|find_path|find_library)\s*\(([^)]*)\)',
                  re.IGNORECASE | re.DOTALL)
keywords = {'REQUIRED', 'QUIET', 'IMPORTED_TARGET', 'GLOBAL', 'NO_CMAKE_PATH', 'NO_CMAKE_ENVIRONMENT_PATH',
            'NO_MODULE', 'CONFIG', 'MODULE', 'EXACT', 'COMPONENTS', 'OPTIONAL_COMPONENTS', 'NAMES', 'HINTS',
            'PATHS', 'PATH_SUFFIXES', 'NO_DEFAULT_PATH', 'DOC'}
import subprocess
def cmake_files():
    # In a checkout: the files git tracks or would track. What it ignores (build trees, the pinned
    # OpenCV's unpacked source in build-opencv/, fetched data) is not the product's, and scanning it
    # made OpenCV's own find_package(Java) a requirement. Elsewhere (a source tarball): every
    # folder but build trees, hidden folders and fetched data.
    listed = subprocess.run(['git', '-C', root, 'ls-files', '-co', '--exclude-standard', '--full-name',
                             '--', ':(glob)**/CMakeLists.txt', ':(glob)**/*.cmake'],
                            capture_output=True, text=True)
    top_level = subprocess.run(['git', '-C', root, 'rev-parse', '--show-toplevel'],
                               capture_output=True, text=True)
    if listed.returncode == 0 and top_level.returncode == 0 and \
            os.path.realpath(top_level.stdout.strip()) == os.path.realpath(root):
        return sorted(os.path.join(root, f) for f in listed.stdout.splitlines() if f)
    found = []
    for top, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if not d.startswith('.') and not d.startswith('build')
                         and d not in ('models', 'data')
                         and not os.path.exists(os.path.join(top, d, 'CMakeCache.txt')))
        found += [os.path.join(top, n) for n in sorted(files)
                  if n == 'CMakeLists.txt' or n.endswith('.cmake')]
    return found
for path in cmake_files():
    text = open(path, encoding='utf-8').read()
    # comments and quoted strings out (a string may hold CMake code), line numbers kept
    text = re.sub(r'"(?:[^"\\]|\\.)*"', lambda m: '\n' * m.group(0).count('\n'), text)
    text = re.sub(r'#[^\n]*', '', text)
    for m in call.finditer(text):
        kind = m.group(1).lower()
        args = m.group(2).split()
        line = text.count('\n', 0, m.start()) + 1
        where = f'{os.path.relpath(path, root)}:{line}'
        if not args:
            continue
        if kind == 'find_package':
            print(f'find_package\t{args[0]}\t{where}\t{args[0]}')
        elif kind in ('pkg_check_modules', 'pkg_search_module'):
            for module in args[1:]:
                if module.upper() in keywords:
                    continue
                module = re.split(r'[<>=]', module)[0]
                print(f'{kind}\t{module}\t{where}\t{args[0]}')
        else:  # find_path / find_library: VAR name | VAR NAMES n1 n2 ...
            rest = args[1:]
            if rest and rest[0].upper() == 'NAMES':
                rest = rest[1:]
            print(f'{kind}\t{rest[0] if rest else "?"}\t{where}\t{args[0]}')
PY
}

# cache BUILD_DIR KEY: the value of KEY in the CMake cache, empty when absent.
cache() {
  sed -n "s|^$2:[A-Z]*=||p" "$1/CMakeCache.txt" | head -n 1
}

# Debian packages owning a path (no architecture suffix), comma-separated. With usrmerge a library
# may be registered under /lib while found under /usr/lib: both are asked.
owner() {
  { dpkg -S "$1" 2>/dev/null || dpkg -S "${1#/usr}" 2>/dev/null || true; } |
    sed 's/: .*//; s/:[a-z0-9]*//g' | tr -d ' ' | tr ',' '\n' | sort -u | paste -sd, -
}

resolve() {
  local build_dir="${1:?usage: gpu_deps.sh resolve BUILD_DIR [SOURCE_DIR]}" source_dir="${2:-$repo}"
  [[ -f $build_dir/CMakeCache.txt ]] || die "$build_dir/CMakeCache.txt: not found (configure the build first)"
  local failed=0 kind name where var file packages dir
  while IFS=$'\t' read -r kind name where var; do
    packages=""
    case $kind in
      find_package)
        if [[ $name =~ $provided_re ]]; then
          packages="(provided on the GPU machine)"
        else
          dir="$(cache "$build_dir" "${name}_DIR")"
          if [[ -n $dir && -d $dir ]]; then
            file="$(ls "$dir"/*[Cc]onfig.cmake 2>/dev/null | head -n 1)"
            [[ -n $file ]] && packages="$(owner "$(readlink -f "$file")")"
          else # module mode (e.g. FindZLIB): the library files it found
            local upper="${name^^}" key
            for key in "${upper}_LIBRARY_RELEASE" "${name}_LIBRARY_RELEASE" "${upper}_LIBRARY" "${name}_LIBRARY" "${upper}_LIBRARIES"; do
              file="$(cache "$build_dir" "$key")"
              if [[ -n $file && -e ${file%%;*} ]]; then
                packages="$(owner "${file%%;*}")"
                break
              fi
            done
          fi
        fi
        ;;
      pkg_check_modules | pkg_search_module)
        file="$(pkg-config --path "$name" 2>/dev/null || true)"
        [[ -n $file ]] && packages="$(owner "$(readlink -f "$file")")"
        ;;
      find_path)
        dir="$(cache "$build_dir" "$var")"
        [[ -n $dir && -e $dir/$name ]] && packages="$(owner "$dir/$name")"
        ;;
      find_library)
        file="$(cache "$build_dir" "$var")"
        [[ -n $file && -e $file ]] && packages="$(owner "$file")"
        ;;
    esac
    if [[ -z $packages ]]; then
      echo "gpu_deps: $where: $kind($name) resolves to no Debian package (not found in $build_dir/CMakeCache.txt or not owned by any installed package)" >&2
      failed=1
    fi
    printf '%s\t%s\t%s\t%s\n' "$kind" "$name" "$where" "$packages"
  done < <(requirements "$source_dir")
  return "$failed"
}

# Every library file a package ships (.so and .so.N), for the ELF closure.
package_libraries() {
  dpkg -L "$1" 2>/dev/null | grep -E '/lib[^/]*\.so(\.[0-9.]+)?$' || true
}

packages() {
  local build_dir="${1:?usage: gpu_deps.sh packages BUILD_DIR}"
  local resolved
  resolved="$(resolve "$build_dir")" || die "requirements unresolved (above)"
  declare -A want=() seed=()
  local p dir lib kind name where packages
  while IFS=$'\t' read -r kind name where packages; do
    [[ $packages == *provided* ]] && continue
    for p in ${packages//,/ }; do want[$p]=1; done
    case $kind in
      pkg_*) # the include folders and the libraries its pkg-config module names (glib's, ...)
        for dir in $(pkg-config --cflags-only-I "$name" | tr ' ' '\n' | sed -n 's/^-I//p'); do
          [[ $dir == /usr/include || $dir == /usr/include/$(gcc -dumpmachine) ]] && continue
          for p in $(owner "$dir" | tr ',' ' '); do want[$p]=1; done
        done
        for lib in $(pkg-config --libs-only-l "$name" | tr ' ' '\n' | sed -n 's/^-l//p'); do
          lib="$(gcc -print-file-name="lib$lib.so")"
          [[ -e $lib ]] && seed[$(readlink -f "$lib")]=1
        done
        ;;
      *) # a CMake package or a library found by path: every library its -dev package ships
        for p in ${packages//,/ }; do
          for lib in $(package_libraries "$p"); do [[ -e $lib ]] && seed[$(readlink -f "$lib")]=1; done
        done
        # and every file its exported targets name (CMake checks they all exist, e.g. ONNX's
        # onnxifi libraries, which another package ships)
        dir="$(cache "$build_dir" "${name}_DIR")"
        if [[ $kind == find_package && -n $dir && -d $dir ]]; then
          local prefix="${dir%%/lib/*}"
          prefix="${prefix%%/share/*}"
          for lib in $(grep -ho '${_IMPORT_PREFIX}/[^" ;)]*' "$dir"/*.cmake 2>/dev/null | sort -u); do
            lib="$prefix${lib#\$\{_IMPORT_PREFIX\}}"
            [[ -f $lib ]] || continue
            for p in $(owner "$lib" | tr ',' ' '); do want[$p]=1; done
            [[ $lib == *.so* ]] && seed[$(readlink -f "$lib")]=1
          done
        fi
        ;;
    esac
  done <<<"$resolved"
  # ELF closure: the libraries linked and every DT_NEEDED of theirs, to a fixed point
  local ld_cache needed path
  ld_cache="$(ldconfig -p)"
  declare -A done_lib=()
  local -a queue=("${!seed[@]}")
  while ((${#queue[@]})); do
    lib="${queue[0]}"
    queue=("${queue[@]:1}")
    [[ -n ${done_lib[$lib]:-} ]] && continue
    done_lib[$lib]=1
    for p in $(owner "$lib" | tr ',' ' '); do want[$p]=1; done
    for needed in $(objdump -p "$lib" 2>/dev/null | awk '$1 == "NEEDED" {print $2}'); do
      path="$(awk -v n="$needed" '$1 == n && $0 ~ /x86-64|x86_64/ {print $NF}' <<<"$ld_cache" | head -n 1)"
      [[ -n $path ]] && queue+=("$(readlink -f "$path")")
    done
  done
  for p in "${!want[@]}"; do echo "$p"; done | grep -Ev "$runtime_re" | sort -u
}

command="${1:-}"
shift || true
case $command in
  requirements) requirements "$@" ;;
  resolve) resolve "$@" ;;
  packages) packages "$@" ;;
  check)
    out="$(resolve "$@")" || {
      echo "gpu_deps: the GPU machine's package set (scripts/gpu_prepare.sh) does not cover the product's CMake requirements: fix the requirement or make it resolvable here (docs/gpu.md)" >&2
      exit 1
    }
    echo "$out"
    echo "gpu_deps: all $(wc -l <<<"$out") CMake requirements resolve to Debian packages or are provided on the GPU machine"
    ;;
  *) die "usage: gpu_deps.sh requirements|resolve|packages|check ... (see the script's header)" ;;
esac
