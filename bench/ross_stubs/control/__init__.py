# bench stub: python-control (not packaged in Debian) is used by ROSS only for
# magnetic-bearing controllers, which the benchmark rotors do not have.
class TransferFunction:
    s = None
def tf(*a, **k): raise NotImplementedError("control stub")
ss = lqr = lqe = sample_system = frequency_response = tf
