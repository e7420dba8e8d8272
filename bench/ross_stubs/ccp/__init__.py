# bench stub: ccp (seals only) is not packaged in Debian
