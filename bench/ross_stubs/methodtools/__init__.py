# bench stub (methodtools is not packaged in Debian): per-call, uncached.
# ROSS uses methodtools.lru_cache on Rotor methods; an uncached call is never faster.
def lru_cache(*args, **kwargs):
    def deco(f):
        return f
    return deco
