"""kits - the code behind tools/make_kit.py and tools/check_kit.py.

    regions.py     the exercise markers and the signatures around them
    repository.py  stages, pages, files, the manifest, every region
    strip.py       a kit's plan: the stubs, the switchable kit, the replaced files
    write.py       the plan written to a folder, or synced into one

tools/kit/ holds the files a kit is given (its README, DEVELOPERS.md, CI script);
this package holds the code.
"""
