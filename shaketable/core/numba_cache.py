"""Where numba caches the package's compiled functions: one folder whatever the install.

numba names the cache folder of a module's compiled functions after the module folder's
*absolute path* (``rocking_<sha1 of /.../shaketable/models/rocking>``, numba's
``_CacheLocator.get_suitable_cache_subpath``), so the same sources installed twice (a
wheel in ``site-packages``, then an editable install of the checkout) compile twice,
although numba's own check of a cached function (the SHA-256 of its file, the bytecode,
the signature, numba's version and the CPU) would accept the first compile. The package's
functions are located here by their folder *inside the package* instead
(``rocking_<sha1 of "shaketable/models/rocking">``): the key is then the sources alone (numba's
check above, and ``NUMBA_CACHE_DIR``'s default folder keyed by the hash of ``core/``,
``models/`` and ``numerics/``, ``shaketable/__init__.py``). Functions outside the package keep numba's
locators. The module imports numba only when :func:`register` is called (by
``models/rocking/physics.py``, which every module that compiles imports before its first
decorator).
"""

from __future__ import annotations

import hashlib
import os

#: The folder that holds the package folder ``shaketable`` (site-packages, or the checkout).
PACKAGE_PARENT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def cache_subpath(module_folder: str) -> str:
    """The cache subfolder of the compiled functions of one package folder.

    Parameters
    ----------
    module_folder : str
        A folder of the package (e.g. ``.../shaketable/models/rocking``), absolute or relative.

    Returns
    -------
    str
        ``<folder name>_<sha1 of its path relative to the package's parent, with "/">``,
        e.g. ``rocking_<sha1 of "shaketable/models/rocking">``: the same for every install.
    """
    folder = os.path.abspath(module_folder)
    relative = os.path.relpath(folder, PACKAGE_PARENT).replace(os.sep, "/")
    return f"{os.path.basename(folder)}_{hashlib.sha1(relative.encode()).hexdigest()}"


def _inside_package(py_file: str) -> bool:
    package = os.path.join(PACKAGE_PARENT, "shaketable")
    return os.path.abspath(py_file).startswith(package + os.sep)


_REGISTERED: list[type] = []


def register() -> None:
    """Have numba locate the cache of the package's functions with :func:`cache_subpath`.

    Puts a locator before numba's own (``CacheImpl._locator_classes``) that answers for the
    package's source files only, when ``NUMBA_CACHE_DIR`` is set (``import shaketable``
    sets it unless the user did); numba's locators serve every other function. Idempotent.
    """
    if _REGISTERED:
        return
    from numba.core import caching

    class PackageCacheLocator(caching.UserProvidedCacheLocator):
        """numba's locator for ``NUMBA_CACHE_DIR``, with the folder named from the package."""

        @classmethod
        def get_suitable_cache_subpath(cls, py_file):
            return cache_subpath(os.path.dirname(os.path.abspath(py_file)))

        @classmethod
        def from_function(cls, py_func, py_file):
            if not _inside_package(py_file):
                return None
            return super().from_function(py_func, py_file)

    caching.CacheImpl._locator_classes.insert(0, PackageCacheLocator)
    _REGISTERED.append(PackageCacheLocator)
